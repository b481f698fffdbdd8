#include "tests/client/viewer/bridge_client.h"

// <utility> before Boost: Boost 1.74's Asio uses std::exchange without it.
#include <utility>

#include <boost/asio.hpp>
#include <boost/asio/ssl/host_name_verification.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/ssl.hpp>
#include <boost/beast/websocket.hpp>
#include <boost/beast/websocket/ssl.hpp>
#include <variant>

#include "absl/strings/ascii.h"

namespace hs::cli::testing {
namespace {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;
namespace ssl = net::ssl;
using tcp = net::ip::tcp;
using TlsStream = beast::ssl_stream<beast::tcp_stream>;

std::string HostOf(uint16_t port) { return "127.0.0.1:" + std::to_string(port); }

// A connected stream: plain, or TLS with the bridge's certificate checked
// against `ca` and 127.0.0.1.
template <class Stream>
bool Connect(Stream& stream, uint16_t port) {
  beast::error_code ec;
  beast::get_lowest_layer(stream).connect(tcp::endpoint(net::ip::make_address("127.0.0.1"), port),
                                          ec);
  if (ec) return false;
  if constexpr (std::is_same_v<Stream, TlsStream>) {
    stream.set_verify_mode(ssl::verify_peer);
    stream.set_verify_callback(ssl::host_name_verification("127.0.0.1"));
    stream.handshake(ssl::stream_base::client, ec);
  }
  return !ec;
}

std::unique_ptr<ssl::context> Trusting(const std::filesystem::path& ca) {
  auto context = std::make_unique<ssl::context>(ssl::context::tls_client);
  context->load_verify_file(ca.string());
  return context;
}

template <class Stream>
HttpReply GetOver(Stream& stream, uint16_t port, const std::string& target) {
  HttpReply reply;
  if (!Connect(stream, port)) return reply;
  http::request<http::empty_body> request(http::verb::get, target, 11);
  request.set(http::field::host, HostOf(port));
  beast::error_code ec;
  http::write(stream, request, ec);
  beast::flat_buffer buffer;
  http::response<http::string_body> response;
  if (!ec) http::read(stream, buffer, response, ec);
  if (ec) return reply;
  reply.status = response.result_int();
  for (const auto& field : response) {
    reply.headers[absl::AsciiStrToLower(std::string(field.name_string()))] =
        std::string(field.value());
  }
  reply.body = response.body();
  return reply;
}

}  // namespace

HttpReply Get(uint16_t port, const std::string& target, const std::filesystem::path& ca) {
  net::io_context io;
  if (ca.empty()) {
    beast::tcp_stream stream(io);
    return GetOver(stream, port, target);
  }
  const auto context = Trusting(ca);
  TlsStream stream(io, *context);
  return GetOver(stream, port, target);
}

struct PageClient::Socket {
  net::io_context io;
  std::unique_ptr<ssl::context> tls;
  std::variant<std::monostate, websocket::stream<beast::tcp_stream>, websocket::stream<TlsStream>>
      ws;
  int status = 0;
  beast::flat_buffer buffer;

  template <class Ws>
  void Open(Ws& w, uint16_t port, const std::string& origin, const std::string& target) {
    if (!Connect(w.next_layer(), port)) return;
    w.set_option(websocket::stream_base::decorator([origin](websocket::request_type& request) {
      if (!origin.empty()) request.set(http::field::origin, origin);
    }));
    // Boost 1.74's blocking handshake drops a refusal's response; the
    // asynchronous one hands it over. No answer at all leaves status 0.
    websocket::response_type response;
    response.result(0);
    w.async_handshake(response, HostOf(port), target, [](beast::error_code) {});
    io.run();
    io.restart();
    status = response.result_int();
  }
};

PageClient::PageClient(uint16_t port, const std::string& origin, const std::string& target,
                       const std::filesystem::path& ca)
    : socket_(std::make_unique<Socket>()) {
  Socket& s = *socket_;
  if (ca.empty()) {
    s.Open(s.ws.emplace<websocket::stream<beast::tcp_stream>>(s.io), port, origin, target);
  } else {
    s.tls = Trusting(ca);
    s.Open(s.ws.emplace<websocket::stream<TlsStream>>(s.io, *s.tls), port, origin, target);
  }
}

PageClient::~PageClient() = default;

int PageClient::status() const { return socket_->status; }

std::string PageClient::Read() {
  return std::visit(
      [this](auto& w) -> std::string {
        if constexpr (std::is_same_v<std::decay_t<decltype(w)>, std::monostate>) {
          return "";
        } else {
          beast::error_code ec;
          socket_->buffer.consume(socket_->buffer.size());
          w.read(socket_->buffer, ec);
          return ec ? "" : beast::buffers_to_string(socket_->buffer.data());
        }
      },
      socket_->ws);
}

void PageClient::Write(const std::string& text) {
  std::visit(
      [&text](auto& w) {
        if constexpr (!std::is_same_v<std::decay_t<decltype(w)>, std::monostate>) {
          beast::error_code ec;
          w.text(true);
          w.write(net::buffer(text), ec);
        }
      },
      socket_->ws);
}

}  // namespace hs::cli::testing
