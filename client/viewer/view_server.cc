#include "client/viewer/view_server.h"

#include <atomic>
#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/ssl.hpp>
#include <boost/beast/websocket.hpp>
#include <boost/beast/websocket/ssl.hpp>
#include <chrono>
#include <deque>
#include <optional>
#include <set>
#include <thread>

#include "absl/strings/str_cat.h"
#include "client/viewer/page_device.h"
#include "client/viewer/page_message.h"
#include "client/viewer/page_policy.h"
#include "client/viewer/viewer_json.h"
#include "client/viewer/web_assets.h"
#include "client/viewer/ws_admission.h"
#include "common/api/proto_convert.h"

namespace hs::cli {
namespace {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;
namespace ssl = net::ssl;
namespace pb = haptics::v1;
using tcp = net::ip::tcp;
using TlsStream = beast::ssl_stream<beast::tcp_stream>;
using nlohmann::json;

// A page sends poses and short commands; anything longer is not one.
constexpr size_t kMaxPageMessageBytes = 16 << 10;
// A request, or a TLS handshake, that takes longer is dropped.
constexpr std::chrono::seconds kRequestTimeout{30};

int64_t UnixNowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

std::shared_ptr<const std::string> Text(const json& message) {
  return std::make_shared<const std::string>(message.dump());
}

// Beast's string_view (Boost's, in Boost 1.74) as the standard one.
std::string_view View(beast::string_view text) { return {text.data(), text.size()}; }

std::string_view IndexHtml() {
  for (const WebAsset& asset : WebAssets()) {
    if (asset.path == "/index.html") return asset.body;
  }
  return {};
}

// The server's TLS context, its files checked as it is made so that a
// wrong one is named now, not in a failed handshake later.
absl::StatusOr<std::unique_ptr<ssl::context>> MakeTlsContext(const ViewServerOptions& options) {
  if (options.tls_cert_file.empty() || options.tls_key_file.empty()) {
    return absl::InvalidArgumentError(
        "TLS needs both a certificate and its key (--http-tls-cert, --http-tls-key)");
  }
  auto context = std::make_unique<ssl::context>(ssl::context::tls_server);
  context->set_options(ssl::context::default_workarounds | ssl::context::no_sslv2 |
                       ssl::context::no_sslv3 | ssl::context::no_tlsv1 | ssl::context::no_tlsv1_1);
  beast::error_code ec;
  context->use_certificate_chain_file(options.tls_cert_file, ec);
  if (ec) {
    return absl::InvalidArgumentError(
        absl::StrCat(options.tls_cert_file, " holds no PEM certificate: ", ec.message()));
  }
  context->use_private_key_file(options.tls_key_file, ssl::context::pem, ec);
  if (ec) {
    return absl::InvalidArgumentError(absl::StrCat(
        options.tls_key_file, " holds no unencrypted PEM private key: ", ec.message()));
  }
  if (SSL_CTX_check_private_key(context->native_handle()) != 1) {
    return absl::InvalidArgumentError(
        absl::StrCat(options.tls_key_file, " is not the private key of ", options.tls_cert_file));
  }
  return context;
}

}  // namespace

class Page;

struct ViewServer::Impl {
  Impl(SceneLink& link_in, const ViewServerOptions& options_in, std::string token,
       std::unique_ptr<ssl::context> tls_in)
      : link(link_in),
        options(options_in),
        admission(std::move(token), tls_in != nullptr),
        security_headers(PageSecurityHeaders(IndexHtml())),
        tls(std::move(tls_in)),
        acceptor(io),
        timer(io) {}

  void Accept();
  // One accepted connection, after its TLS handshake when there is TLS.
  void Serve(tcp::socket socket);
  void Tick();
  json Hello(const SceneLink::State& s) const;
  json Status(const SceneLink::State& s) const;
  // The tools this bridge's pages hold -> "viewer page N" (the frames name
  // the other tools' holders).
  std::map<std::string, std::string> PageHolders() const;

  SceneLink& link;
  const ViewServerOptions options;
  const WsAdmission admission;
  const std::vector<std::pair<std::string, std::string>> security_headers;
  // Before io: its streams end with io.
  const std::unique_ptr<ssl::context> tls;
  net::io_context io;
  tcp::acceptor acceptor;
  net::steady_timer timer;
  std::thread thread;
  // Everything below: the io thread only, but for the atomics.
  std::set<std::shared_ptr<Page>> pages;
  int next_page_id = 1;
  uint64_t last_frame_count = 0;
  bool last_connected = false;
  int64_t last_revision = -1;
  std::string last_message;
  std::atomic<int64_t> open_pages{0};
  std::atomic<int64_t> rejected{0};
  std::atomic<int64_t> forwarded{0};
};

// One page's WebSocket, whatever carries it (PageSocket below): its
// messages in, the newest frame out.
class Page : public std::enable_shared_from_this<Page> {
 public:
  Page(ViewServer::Impl& server, int id) : server_(server), id_(id) {}
  virtual ~Page() = default;

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
    writing_ = true;
    Write(std::move(message));
  }

  const std::string& held_tool() const { return held_tool_; }
  // A held tool's pose goes out again after half a second without one.
  void KeepDeviceAlive() {
    if (device_ && !held_tool_.empty()) device_->KeepAlive(std::chrono::milliseconds(500));
  }
  uint64_t replaced() const { return replaced_; }
  int id() const { return id_; }

 protected:
  // Writes one message; calls Written when done.
  virtual void Write(std::shared_ptr<const std::string> message) = 0;
  // Reads the next message; calls Received with it, or Close.
  virtual void Read() = 0;

  // The upgrade is done: the page is counted and greeted, then heard.
  void Opened() {
    server_.pages.insert(shared_from_this());
    ++server_.open_pages;
    const SceneLink::State s = server_.link.state();
    Send(Text(server_.Hello(s)));
    Send(Text(server_.Status(s)));
    Read();
  }

  void Written(beast::error_code ec) {
    writing_ = false;
    if (ec) return Close();
    if (queue_.empty()) return;
    auto next = std::move(queue_.front().first);
    queue_.pop_front();
    writing_ = true;
    Write(std::move(next));
  }

  void Received(bool is_text, const std::string& message) {
    if (!is_text) {
      ++server_.rejected;
    } else {
      Handle(message);
    }
  }

  void Close() {
    if (closed_) return;
    closed_ = true;
    if (server_.pages.erase(shared_from_this()) > 0) --server_.open_pages;
    device_.reset();
  }

 private:
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
    std::weak_ptr<Page> weak = weak_from_this();
    net::io_context& io = server_.io;
    device_ = std::make_unique<PageDevice>(
        server_.link.channel(), server_.link.scene(), tool,
        [weak, &io, tool, stream](const std::string& state, const std::string& why) {
          net::post(io, [weak, tool, stream, state, why] {
            if (auto self = weak.lock()) self->Reported(stream, tool, state, why);
          });
        },
        WatchedDevicePose(tool));
  }

  // `tool`'s device pose in the latest frame watched, if it has one.
  std::optional<Isometry3d> WatchedDevicePose(const std::string& tool) const {
    const std::shared_ptr<const pb::Frame> frame = server_.link.latest().frame;
    if (!frame) return std::nullopt;
    for (const pb::ToolState& state : frame->tools()) {
      if (state.tool() != tool || !state.has_device_pose()) continue;
      absl::StatusOr<Isometry3d> X_WD = PoseFromProto(state.device_pose(), "watched pose");
      if (X_WD.ok()) return *X_WD;
    }
    return std::nullopt;
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

  ViewServer::Impl& server_;
  const int id_;
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

// A page's WebSocket over `Stream`: beast::tcp_stream, or TlsStream.
template <class Stream>
class PageSocket final : public Page {
 public:
  PageSocket(ViewServer::Impl& server, Stream stream, int id)
      : Page(server, id), ws_(std::move(stream)) {}

  void Accept(http::request<http::string_body> request) {
    ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
    ws_.read_message_max(kMaxPageMessageBytes);
    ws_.async_accept(request, [self = Self()](beast::error_code ec) {
      if (!ec) self->Opened();
    });
  }

 private:
  std::shared_ptr<PageSocket> Self() {
    return std::static_pointer_cast<PageSocket>(shared_from_this());
  }

  void Write(std::shared_ptr<const std::string> message) override {
    ws_.text(true);
    ws_.async_write(net::buffer(*message),
                    [self = Self(), message](beast::error_code ec, size_t) { self->Written(ec); });
  }

  void Read() override {
    ws_.async_read(buffer_, [self = Self()](beast::error_code ec, size_t) {
      if (ec) return self->Close();
      self->Received(self->ws_.got_text(), beast::buffers_to_string(self->buffer_.data()));
      self->buffer_.consume(self->buffer_.size());
      self->Read();
    });
  }

  websocket::stream<Stream> ws_;
  beast::flat_buffer buffer_;
};

// One HTTP connection over `Stream` (beast::tcp_stream or TlsStream):
// assets, /geometry and /frame, or the upgrade to a page's WebSocket.
template <class Stream>
class HttpSession : public std::enable_shared_from_this<HttpSession<Stream>> {
 public:
  HttpSession(ViewServer::Impl& server, Stream stream)
      : server_(server), stream_(std::move(stream)) {}

  void Read() {
    request_ = {};
    beast::get_lowest_layer(stream_).expires_after(kRequestTimeout);
    http::async_read(stream_, buffer_, request_,
                     [self = this->shared_from_this()](beast::error_code ec, size_t) {
                       if (ec) return;
                       self->Handle();
                     });
  }

 private:
  void Handle() {
    std::string target(request_.target());
    target = target.substr(0, target.find('?'));
    if (websocket::is_upgrade(request_)) {
      if (target != "/ws") return Respond(http::status::not_found, "no such socket");
      const absl::Status admitted =
          server_.admission.Admit(View(request_[http::field::origin]),
                                  View(request_[http::field::host]), View(request_.target()));
      if (!admitted.ok()) return Refuse(admitted);
      beast::get_lowest_layer(stream_).expires_never();
      std::make_shared<PageSocket<Stream>>(server_, std::move(stream_), server_.next_page_id++)
          ->Accept(std::move(request_));
      return;
    }
    if (request_.method() != http::verb::get && request_.method() != http::verb::head) {
      return Respond(http::status::method_not_allowed, "GET only");
    }
    if (target == "/") target = "/index.html";
    if (target == "/geometry" || target == "/frame") {
      if (absl::Status known = server_.admission.CheckToken(View(request_.target())); !known.ok()) {
        return Refuse(known);
      }
    }
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

  // 403, saying why and how to get in.
  void Refuse(const absl::Status& why) {
    Respond(http::status::forbidden,
            absl::StrCat(why.message(),
                         ": open the page at the address hapticctl view printed, "
                         "with its ?token="));
  }

  void Send(http::status status, const std::string& type, std::string body) {
    auto response = std::make_shared<http::response<http::string_body>>(status, request_.version());
    response->set(http::field::content_type, type);
    response->set(http::field::cache_control, "no-store");
    for (const auto& [name, value] : server_.security_headers) response->set(name, value);
    response->keep_alive(request_.keep_alive());
    response->body() = request_.method() == http::verb::head ? "" : std::move(body);
    response->prepare_payload();
    http::async_write(stream_, *response,
                      [self = this->shared_from_this(), response](beast::error_code ec, size_t) {
                        if (ec || !response->keep_alive()) return;
                        self->Read();
                      });
  }

  ViewServer::Impl& server_;
  Stream stream_;
  beast::flat_buffer buffer_;
  http::request<http::string_body> request_;
};

void ViewServer::Impl::Accept() {
  acceptor.async_accept([this](beast::error_code ec, tcp::socket socket) {
    if (ec == net::error::operation_aborted) return;
    if (!ec) Serve(std::move(socket));
    Accept();
  });
}

void ViewServer::Impl::Serve(tcp::socket socket) {
  if (!tls) {
    std::make_shared<HttpSession<beast::tcp_stream>>(*this, beast::tcp_stream(std::move(socket)))
        ->Read();
    return;
  }
  auto stream = std::make_shared<TlsStream>(std::move(socket), *tls);
  beast::get_lowest_layer(*stream).expires_after(kRequestTimeout);
  stream->async_handshake(ssl::stream_base::server, [this, stream](beast::error_code ec) {
    if (!ec) std::make_shared<HttpSession<TlsStream>>(*this, std::move(*stream))->Read();
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
  std::unique_ptr<ssl::context> tls;
  if (!options.tls_cert_file.empty() || !options.tls_key_file.empty()) {
    absl::StatusOr<std::unique_ptr<ssl::context>> made = MakeTlsContext(options);
    if (!made.ok()) return made.status();
    tls = std::move(*made);
  }
  absl::StatusOr<std::string> token = NewViewToken();
  if (!token.ok()) return token.status();
  auto impl = std::make_unique<Impl>(link, options, std::move(*token), std::move(tls));
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

const std::string& ViewServer::token() const { return impl_->admission.token(); }

std::string ViewServer::url() const {
  const std::string& host = impl_->options.host;
  return absl::StrCat(impl_->tls ? "https" : "http", "://",
                      host.find(':') == std::string::npos ? host : "[" + host + "]", ":", port(),
                      "/?token=", token());
}

ViewServer::Counters ViewServer::counters() const {
  return {impl_->open_pages.load(), impl_->rejected.load(), impl_->forwarded.load()};
}

}  // namespace hs::cli
