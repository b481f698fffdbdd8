#include "tests/server/agones/fake_agones_sdk.h"

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <chrono>

namespace hs::testing {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
using tcp = asio::ip::tcp;

struct FakeAgonesSdk::Listener {
  asio::io_context io;
  tcp::acceptor acceptor{io, tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0)};
};

FakeAgonesSdk::FakeAgonesSdk() : listener_(std::make_unique<Listener>()) {
  port_ = listener_->acceptor.local_endpoint().port();
  thread_ = std::thread([this] { Serve(); });
}

FakeAgonesSdk::~FakeAgonesSdk() {
  stop_ = true;
  // Wakes the blocking accept with a connection of its own.
  boost::system::error_code ignored;
  tcp::socket wake(listener_->io);
  wake.connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), port_), ignored);
  thread_.join();
}

void FakeAgonesSdk::Serve() {
  while (!stop_) {
    tcp::socket socket(listener_->io);
    boost::system::error_code error;
    listener_->acceptor.accept(socket, error);
    if (error || stop_) continue;
    // Requests on this connection until the client closes it.
    beast::flat_buffer buffer;
    for (;;) {
      http::request<http::string_body> request;
      http::read(socket, buffer, request, error);
      if (error) break;
      {
        std::lock_guard lock(mu_);
        requests_.push_back(
            {std::string(request.method_string()), std::string(request.target()), request.body()});
      }
      cv_.notify_all();
      http::response<http::string_body> response(
          failing_ ? http::status::service_unavailable : http::status::ok, request.version());
      response.set(http::field::content_type, "application/json");
      response.body() = "{}";
      response.keep_alive(request.keep_alive());
      response.prepare_payload();
      http::write(socket, response, error);
      if (error || !request.keep_alive()) break;
    }
  }
}

std::vector<FakeAgonesSdk::Request> FakeAgonesSdk::requests() const {
  std::lock_guard lock(mu_);
  return requests_;
}

int FakeAgonesSdk::Count(const std::string& method, const std::string& target) const {
  std::lock_guard lock(mu_);
  return CountLocked(method, target);
}

int FakeAgonesSdk::CountLocked(const std::string& method, const std::string& target) const {
  int n = 0;
  for (const Request& r : requests_) n += r.method == method && r.target == target;
  return n;
}

bool FakeAgonesSdk::WaitFor(const std::string& method, const std::string& target, int count,
                            double timeout_s) const {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  std::unique_lock lock(mu_);
  return cv_.wait_until(lock, deadline, [&] { return CountLocked(method, target) >= count; });
}

}  // namespace hs::testing
