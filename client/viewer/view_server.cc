#include "client/viewer/view_server.h"

#include <atomic>
#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <deque>
#include <iostream>
#include <set>
#include <thread>

#include "client/viewer/page_device.h"
#include "client/viewer/page_message.h"
#include "client/viewer/viewer_json.h"
#include "client/viewer/web_assets.h"

namespace hs::cli {
namespace {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;
using tcp = net::ip::tcp;
using nlohmann::json;

// A page sends poses and short commands; anything longer is not one.
constexpr size_t kMaxPageMessageBytes = 16 << 10;

int64_t UnixNowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

std::shared_ptr<const std::string> Text(const json& message) {
  return std::make_shared<const std::string>(message.dump());
}

}  // namespace

class PageSocket;

struct ViewServer::Impl {
  Impl(SceneLink& link_in, const ViewServerOptions& options_in)
      : link(link_in), options(options_in), acceptor(io), timer(io) {}

  void Accept();
  void Tick();
  json Hello(const SceneLink::State& s) const;
  json Status(const SceneLink::State& s) const;
  // The tools this bridge's pages hold -> "viewer page N" (the frames name
  // the other tools' holders).
  std::map<std::string, std::string> PageHolders() const;

  SceneLink& link;
  const ViewServerOptions options;
  net::io_context io;
  tcp::acceptor acceptor;
  net::steady_timer timer;
  std::thread thread;
  // Everything below: the io thread only, but for the atomics.
  std::set<std::shared_ptr<PageSocket>> pages;
  int next_page_id = 1;
  uint64_t last_frame_count = 0;
  bool last_connected = false;
  int64_t last_revision = -1;
  std::string last_message;
  std::atomic<int64_t> open_pages{0};
  std::atomic<int64_t> rejected{0};
  std::atomic<int64_t> forwarded{0};
};

// One page's WebSocket: its messages in, the newest frame out.
class PageSocket : public std::enable_shared_from_this<PageSocket> {
 public:
  PageSocket(ViewServer::Impl& server, tcp::socket socket, int id)
      : server_(server), ws_(std::move(socket)), id_(id) {}

  void Accept(http::request<http::string_body> request) {
    ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
    ws_.read_message_max(kMaxPageMessageBytes);
    ws_.async_accept(request, [self = shared_from_this()](beast::error_code ec) {
      if (ec) return;
      self->server_.pages.insert(self);
      ++self->server_.open_pages;
      const SceneLink::State s = self->server_.link.state();
      self->Send(Text(self->server_.Hello(s)));
      self->Send(Text(self->server_.Status(s)));
      self->Read();
    });
  }

  // Queues `message`; a frame still waiting behind a write is replaced
  // (latest wins) and counted.
  void Send(std::shared_ptr<const std::string> message, bool is_frame = false) {
    if (writing_) {
      if (is_frame) {
        for (auto& waiting : queue_) {
          if (waiting.second) {
            waiting.first = std::move(message);
            ++replaced_;
            return;
          }
        }
      }
      queue_.emplace_back(std::move(message), is_frame);
      return;
    }
    Write(std::move(message));
  }

  const std::string& held_tool() const { return held_tool_; }
  // A held tool's pose goes out again after half a second without one.
  void KeepDeviceAlive() {
    if (device_ && !held_tool_.empty()) device_->KeepAlive(std::chrono::milliseconds(500));
  }
  uint64_t replaced() const { return replaced_; }
  int id() const { return id_; }

 private:
  void Write(std::shared_ptr<const std::string> message) {
    writing_ = true;
    ws_.text(true);
    ws_.async_write(net::buffer(*message),
                    [self = shared_from_this(), message](beast::error_code ec, size_t) {
                      self->writing_ = false;
                      if (ec) return self->Close();
                      if (self->queue_.empty()) return;
                      auto next = std::move(self->queue_.front().first);
                      self->queue_.pop_front();
                      self->Write(std::move(next));
                    });
  }

  void Read() {
    ws_.async_read(buffer_, [self = shared_from_this()](beast::error_code ec, size_t) {
      if (ec) return self->Close();
      if (!self->ws_.got_text()) {
        ++self->server_.rejected;
      } else {
        self->Handle(beast::buffers_to_string(self->buffer_.data()));
      }
      self->buffer_.consume(self->buffer_.size());
      self->Read();
    });
  }

  void Handle(const std::string& text) {
    absl::StatusOr<PageMessage> message = ParsePageMessage(text);
    if (!message.ok()) {
      ++server_.rejected;
      return;
    }
    if (auto* take = std::get_if<TakeTool>(&*message)) return Take(take->tool);
    if (auto* release = std::get_if<ReleaseTool>(&*message)) {
      if (device_ && device_->tool() == release->tool) {
        device_.reset();  // its stream's end is told as "released"
        held_tool_.clear();
      }
      return;
    }
    const MoveTool& move = std::get<MoveTool>(*message);
    if (!device_ || device_->tool() != move.tool || held_tool_ != move.tool) {
      ++server_.rejected;  // not this page's tool (yet)
      return;
    }
    device_->SendPose(move.X_WD);
    ++server_.forwarded;
  }

  void Take(const std::string& tool) {
    device_.reset();
    held_tool_.clear();
    const uint64_t stream = ++stream_;
    std::weak_ptr<PageSocket> weak = weak_from_this();
    net::io_context& io = server_.io;
    device_ = std::make_unique<PageDevice>(
        server_.link.channel(), server_.link.scene(), tool,
        [weak, &io, tool, stream](const std::string& state, const std::string& why) {
          net::post(io, [weak, tool, stream, state, why] {
            if (auto self = weak.lock()) self->Reported(stream, tool, state, why);
          });
        });
  }

  // Stream `stream`'s word on `tool`, on the io thread. A stream released or
  // replaced since (Release, another Take) has its end told, nothing more.
  void Reported(uint64_t stream, const std::string& tool, const std::string& state,
                const std::string& why) {
    const bool current = device_ && stream == stream_;
    if (!current && state == "held") return;
    if (state == "held") {
      held_tool_ = tool;
    } else if (current) {
      held_tool_.clear();
      // Ends on the io thread: its reader thread has returned from Report.
      auto ended = std::move(device_);
      net::post(server_.io, [ended = std::shared_ptr<PageDevice>(std::move(ended))] {});
    }
    Send(Text({{"type", "drive"}, {"tool", tool}, {"state", state}, {"message", why}}));
  }

  void Close() {
    if (closed_) return;
    closed_ = true;
    if (server_.pages.erase(shared_from_this()) > 0) --server_.open_pages;
    device_.reset();
  }

  ViewServer::Impl& server_;
  websocket::stream<beast::tcp_stream> ws_;
  const int id_;
  beast::flat_buffer buffer_;
  bool writing_ = false;
  bool closed_ = false;
  // Messages waiting behind the write under way; true: a frame.
  std::deque<std::pair<std::shared_ptr<const std::string>, bool>> queue_;
  uint64_t replaced_ = 0;
  std::unique_ptr<PageDevice> device_;
  // Counts the page's Takes: which stream a report is from.
  uint64_t stream_ = 0;
  std::string held_tool_;
};

// One HTTP connection: assets, /geometry and /frame, or the upgrade to a
// page's WebSocket.
class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(ViewServer::Impl& server, tcp::socket socket)
      : server_(server), stream_(std::move(socket)) {}

  void Read() {
    request_ = {};
    stream_.expires_after(std::chrono::seconds(30));
    http::async_read(stream_, buffer_, request_,
                     [self = shared_from_this()](beast::error_code ec, size_t) {
                       if (ec) return;
                       self->Handle();
                     });
  }

 private:
  void Handle() {
    if (websocket::is_upgrade(request_)) {
      if (request_.target() != "/ws") return Respond(http::status::not_found, "no such socket");
      stream_.expires_never();
      std::make_shared<PageSocket>(server_, stream_.release_socket(), server_.next_page_id++)
          ->Accept(std::move(request_));
      return;
    }
    if (request_.method() != http::verb::get && request_.method() != http::verb::head) {
      return Respond(http::status::method_not_allowed, "GET only");
    }
    std::string target(request_.target());
    target = target.substr(0, target.find('?'));
    if (target == "/") target = "/index.html";
    if (target == "/geometry") {
      const SceneLink::State s = server_.link.state();
      if (!s.geometry_json) return Respond(http::status::bad_gateway, s.message);
      return Send(http::status::ok, "application/json", *s.geometry_json);
    }
    if (target == "/frame") {
      const SceneLink::Latest latest = server_.link.latest();
      if (!latest.frame) return Respond(http::status::service_unavailable, "no frame yet");
      const SceneLink::State s = server_.link.state();
      FrameExtras extras{.step_rate_hz = latest.step_rate_hz,
                         .dropped_frames = latest.frame->dropped_frames(),
                         .revision = s.revision,
                         .page_holders = server_.PageHolders()};
      return Send(http::status::ok, "application/json", FrameJson(*latest.frame, extras).dump());
    }
    for (const WebAsset& asset : WebAssets()) {
      if (asset.path == target) {
        return Send(http::status::ok, std::string(asset.content_type), std::string(asset.body));
      }
    }
    Respond(http::status::not_found, "not found: " + target);
  }

  void Respond(http::status status, const std::string& error) {
    Send(status, "application/json", json{{"error", error}}.dump());
  }

  void Send(http::status status, const std::string& type, std::string body) {
    auto response = std::make_shared<http::response<http::string_body>>(status, request_.version());
    response->set(http::field::content_type, type);
    response->set(http::field::cache_control, "no-store");
    response->keep_alive(request_.keep_alive());
    response->body() = request_.method() == http::verb::head ? "" : std::move(body);
    response->prepare_payload();
    http::async_write(stream_, *response,
                      [self = shared_from_this(), response](beast::error_code ec, size_t) {
                        if (ec || !response->keep_alive()) return;
                        self->Read();
                      });
  }

  ViewServer::Impl& server_;
  beast::tcp_stream stream_;
  beast::flat_buffer buffer_;
  http::request<http::string_body> request_;
};

void ViewServer::Impl::Accept() {
  acceptor.async_accept([this](beast::error_code ec, tcp::socket socket) {
    if (ec == net::error::operation_aborted) return;
    if (!ec) std::make_shared<HttpSession>(*this, std::move(socket))->Read();
    Accept();
  });
}

json ViewServer::Impl::Hello(const SceneLink::State& s) const {
  return {{"type", "hello"}, {"scene", s.scene}, {"tools", s.tools}, {"step_s", s.step_s}};
}

json ViewServer::Impl::Status(const SceneLink::State& s) const {
  return {{"type", "status"}, {"connected", s.connected}, {"message", s.message}};
}

std::map<std::string, std::string> ViewServer::Impl::PageHolders() const {
  std::map<std::string, std::string> holders;
  for (const auto& page : pages) {
    if (!page->held_tool().empty())
      holders[page->held_tool()] = "viewer page " + std::to_string(page->id());
  }
  return holders;
}

void ViewServer::Impl::Tick() {
  timer.expires_after(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(1.0 / options.send_hz)));
  timer.async_wait([this](beast::error_code ec) {
    if (ec) return;
    const SceneLink::State s = link.state();
    // A new revision may add or remove tools: the pages hear the list again.
    const bool changed = s.connected != last_connected || s.message != last_message;
    if (changed || s.revision != last_revision) {
      last_connected = s.connected;
      last_message = s.message;
      last_revision = s.revision;
      const auto status = Text(Status(s));
      const auto hello = Text(Hello(s));
      for (const auto& page : pages) {
        if (s.connected) page->Send(hello);
        if (changed) page->Send(status);
      }
    }
    for (const auto& page : pages) page->KeepDeviceAlive();
    const SceneLink::Latest latest = link.latest();
    if (latest.frame && latest.count != last_frame_count && !pages.empty()) {
      last_frame_count = latest.count;
      FrameExtras extras{.age_ms = 1e-6 * static_cast<double>(
                                              UnixNowNs() - latest.frame->timings().sent_unix_ns()),
                         .step_rate_hz = latest.step_rate_hz,
                         .revision = s.revision,
                         .page_holders = PageHolders()};
      json frame = FrameJson(*latest.frame, extras);
      frame["rejected_messages"] = rejected.load();
      for (const auto& page : pages) {
        frame["dropped_frames"] = latest.frame->dropped_frames() + page->replaced();
        page->Send(Text(frame), /*is_frame=*/true);
      }
    }
    Tick();
  });
}

absl::StatusOr<std::unique_ptr<ViewServer>> ViewServer::Start(SceneLink& link,
                                                              const ViewServerOptions& options) {
  auto impl = std::make_unique<Impl>(link, options);
  beast::error_code ec;
  const net::ip::address address = net::ip::make_address(options.host, ec);
  if (ec) return absl::InvalidArgumentError("bad listening address '" + options.host + "'");
  const tcp::endpoint endpoint(address, options.port);
  impl->acceptor.open(endpoint.protocol(), ec);
  if (!ec) impl->acceptor.set_option(net::socket_base::reuse_address(true), ec);
  if (!ec) impl->acceptor.bind(endpoint, ec);
  if (!ec) impl->acceptor.listen(net::socket_base::max_listen_connections, ec);
  if (ec) {
    return absl::UnavailableError("cannot listen on " + options.host + ":" +
                                  std::to_string(options.port) + ": " + ec.message());
  }
  impl->Accept();
  impl->Tick();
  Impl* raw = impl.get();
  impl->thread = std::thread([raw] { raw->io.run(); });
  return std::unique_ptr<ViewServer>(new ViewServer(std::move(impl)));
}

ViewServer::ViewServer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

ViewServer::~ViewServer() {
  net::post(impl_->io, [impl = impl_.get()] {
    beast::error_code ignored;
    impl->acceptor.close(ignored);
    impl->timer.cancel();
    impl->pages.clear();
    impl->io.stop();
  });
  impl_->thread.join();
}

uint16_t ViewServer::port() const { return impl_->acceptor.local_endpoint().port(); }

ViewServer::Counters ViewServer::counters() const {
  return {impl_->open_pages.load(), impl_->rejected.load(), impl_->forwarded.load()};
}

}  // namespace hs::cli
