#include "client/relay/tcp_relay.h"

#include <algorithm>
#include <atomic>
#include <boost/asio.hpp>
#include <chrono>
#include <deque>
#include <optional>
#include <thread>
#include <vector>

#include "absl/strings/str_cat.h"
#include "client/remote/link_schedule.h"
#include "common/net/address.h"

namespace hs::cli {
namespace {

namespace net = boost::asio;
using tcp = net::ip::tcp;
using Clock = std::chrono::steady_clock;
using boost::system::error_code;

// The most one read takes: a chunk of the stream, held and released whole.
constexpr size_t kChunkBytes = 16 << 10;

// `address` as an endpoint, refusing one off loopback unless `allow_remote`
// (checked before any name is looked up, and again on what it resolved to).
absl::StatusOr<tcp::endpoint> Resolve(net::io_context& io, const char* flag,
                                      const std::string& address, bool allow_remote) {
  const std::optional<HostPort> split = SplitHostPort(address);
  if (!split) {
    return absl::InvalidArgumentError(
        absl::StrCat(flag, " must be HOST:PORT, not '", address, "'"));
  }
  const std::string refused =
      absl::StrCat(flag, " ", address, " is not on loopback: give --allow-remote to relay it");
  if (!allow_remote && !IsLoopbackAddress(address)) return absl::InvalidArgumentError(refused);
  error_code ec;
  tcp::resolver resolver(io);
  const tcp::resolver::results_type found = resolver.resolve(
      split->host, std::to_string(split->port), tcp::resolver::numeric_service, ec);
  if (ec || found.empty()) {
    return absl::InvalidArgumentError(
        absl::StrCat(flag, " ", address, " does not resolve: ", ec.message()));
  }
  const tcp::endpoint endpoint = found.begin()->endpoint();
  if (!allow_remote && !endpoint.address().is_loopback()) {
    return absl::InvalidArgumentError(refused);
  }
  return endpoint;
}

absl::Status CheckOptions(const RelayOptions& o) {
  if (!(o.one_way_ms >= 0 && o.one_way_ms <= kMaxLinkMs / 2)) {
    return absl::InvalidArgumentError(absl::StrCat("one-way latency must be a number in [0, ",
                                                   kMaxLinkMs / 2, "], not ", o.one_way_ms));
  }
  if (o.max_in_flight_bytes < kChunkBytes) {
    return absl::InvalidArgumentError(
        absl::StrCat("max in-flight bytes must be at least ", kChunkBytes));
  }
  return CheckLinkConditions({.latency_ms = 2 * o.one_way_ms,
                              .jitter_ms = o.jitter_ms,
                              .stall_prob = o.stall_prob,
                              .stall_ms = o.stall_ms});
}

}  // namespace

class Connection;

struct TcpRelay::Impl {
  explicit Impl(const RelayOptions& options_in) : options(options_in), acceptor(io) {}

  void Accept();
  // Seconds since the relay started: the clock of the links' schedules.
  double NowS() const { return std::chrono::duration<double>(Clock::now() - t0).count(); }
  Clock::time_point At(double s) const {
    return t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
  }
  void NotePeak(int64_t bytes) {
    if (bytes > peak_in_flight.load()) peak_in_flight = bytes;  // written on the io thread only
  }

  const RelayOptions options;
  const Clock::time_point t0 = Clock::now();
  net::io_context io;
  tcp::acceptor acceptor;
  tcp::endpoint to;
  uint16_t port = 0;
  std::thread thread;
  // The io thread only.
  std::vector<std::weak_ptr<Connection>> connections;
  uint64_t next_connection = 0;
  std::atomic<int64_t> accepted{0}, bytes_up{0}, bytes_down{0}, stalls{0}, peak_in_flight{0};
};

// One client's connection and the one the relay opened for it, and the two
// directions between them: 0 from the client (up), 1 back to it (down).
class Connection : public std::enable_shared_from_this<Connection> {
 public:
  Connection(TcpRelay::Impl& relay, tcp::socket client, uint64_t number)
      : relay_(relay),
        client_(std::move(client)),
        server_(relay.io),
        directions_{Direction(relay, client_, server_, number * 2),
                    Direction(relay, server_, client_, number * 2 + 1)} {}

  void Start() {
    server_.async_connect(relay_.to, [self = shared_from_this()](const error_code& ec) {
      if (ec || self->closed_) return self->Close();
      error_code ignored;
      // Chunks go out when released, not when Nagle lets them.
      self->client_.set_option(tcp::no_delay(true), ignored);
      self->server_.set_option(tcp::no_delay(true), ignored);
      for (int d = 0; d < 2; ++d) self->Read(d);
    });
  }

  void Close() {
    if (closed_) return;
    closed_ = true;
    error_code ignored;
    client_.close(ignored);
    server_.close(ignored);
    for (Direction& d : directions_) d.timer.cancel();
  }

 private:
  struct Chunk {
    Clock::time_point release;
    std::vector<char> bytes;
  };
  struct Direction {
    Direction(TcpRelay::Impl& relay, tcp::socket& from_in, tcp::socket& to_in, uint64_t stream)
        : from(from_in),
          to(to_in),
          schedule(LinkConditions{.latency_ms = 2 * relay.options.one_way_ms,
                                  .jitter_ms = relay.options.jitter_ms,
                                  .stall_prob = relay.options.stall_prob,
                                  .stall_ms = relay.options.stall_ms,
                                  .seed = relay.options.seed},
                   stream),
          timer(relay.io) {}
    tcp::socket& from;
    tcp::socket& to;
    LinkSchedule schedule;
    net::steady_timer timer;
    std::vector<char> reading;
    std::deque<Chunk> chunks;
    size_t in_flight = 0;
    bool read_pending = false, ended = false, timer_set = false, writing = false, shut = false;
  };

  // What a chunk of `n` bytes costs to hold: its bytes and its bookkeeping,
  // so that many small chunks cannot hold more memory than the cap says.
  static size_t Held(size_t n) { return n + sizeof(Chunk); }

  // Reads the next chunk, unless one is being read, the stream ended or
  // the direction holds its fill.
  void Read(int i) {
    Direction& d = directions_[i];
    const size_t cap = relay_.options.max_in_flight_bytes;
    if (closed_ || d.read_pending || d.ended || d.in_flight + Held(1) > cap) return;
    d.read_pending = true;
    d.reading.resize(std::min(kChunkBytes, cap - d.in_flight - Held(0)));
    d.from.async_read_some(
        net::buffer(d.reading),
        [self = shared_from_this(), i](const error_code& ec, size_t n) { self->OnRead(i, ec, n); });
  }

  void OnRead(int i, const error_code& ec, size_t n) {
    Direction& d = directions_[i];
    d.read_pending = false;
    if (closed_) return;
    if (ec && ec != net::error::eof) return Close();
    if (ec) {
      d.ended = true;
    } else {
      const int64_t stalls_before = d.schedule.stalled();
      const double release = *d.schedule.Release(relay_.NowS());
      relay_.stalls += d.schedule.stalled() - stalls_before;
      d.chunks.push_back(
          {relay_.At(release), std::vector<char>(d.reading.begin(), d.reading.begin() + n)});
      d.in_flight += Held(n);
      relay_.NotePeak(static_cast<int64_t>(d.in_flight));
      Read(i);
    }
    Write(i);
  }

  // Writes the first chunk once it is released; after the last, passes
  // the end of the stream on.
  void Write(int i) {
    Direction& d = directions_[i];
    if (closed_ || d.writing || d.timer_set) return;
    if (d.chunks.empty()) {
      if (d.ended && !d.shut) {
        d.shut = true;
        error_code ignored;
        d.to.shutdown(tcp::socket::shutdown_send, ignored);
        if (directions_[1 - i].shut) Close();
      }
      return;
    }
    if (d.chunks.front().release > Clock::now()) {
      d.timer_set = true;
      d.timer.expires_at(d.chunks.front().release);
      d.timer.async_wait([self = shared_from_this(), i](const error_code&) {
        self->directions_[i].timer_set = false;
        self->Write(i);
      });
      return;
    }
    d.writing = true;
    net::async_write(d.to, net::buffer(d.chunks.front().bytes),
                     [self = shared_from_this(), i](const error_code& ec, size_t n) {
                       self->OnWritten(i, ec, n);
                     });
  }

  void OnWritten(int i, const error_code& ec, size_t n) {
    Direction& d = directions_[i];
    d.writing = false;
    if (closed_) return;
    if (ec) return Close();
    (i == 0 ? relay_.bytes_up : relay_.bytes_down) += static_cast<int64_t>(n);
    d.in_flight -= Held(d.chunks.front().bytes.size());
    d.chunks.pop_front();
    Read(i);
    Write(i);
  }

  TcpRelay::Impl& relay_;
  tcp::socket client_;
  tcp::socket server_;
  Direction directions_[2];
  bool closed_ = false;
};

void TcpRelay::Impl::Accept() {
  acceptor.async_accept([this](const error_code& ec, tcp::socket socket) {
    if (ec == net::error::operation_aborted) return;
    if (!ec) {
      std::erase_if(connections, [](const std::weak_ptr<Connection>& c) { return c.expired(); });
      auto connection = std::make_shared<Connection>(*this, std::move(socket), next_connection++);
      connections.push_back(connection);
      ++accepted;
      connection->Start();
    }
    Accept();
  });
}

absl::StatusOr<std::unique_ptr<TcpRelay>> TcpRelay::Start(const RelayOptions& options) {
  if (absl::Status s = CheckOptions(options); !s.ok()) return s;
  auto impl = std::make_unique<Impl>(options);
  absl::StatusOr<tcp::endpoint> listen =
      Resolve(impl->io, "--listen", options.listen, options.allow_remote);
  if (!listen.ok()) return listen.status();
  absl::StatusOr<tcp::endpoint> to = Resolve(impl->io, "--to", options.to, options.allow_remote);
  if (!to.ok()) return to.status();
  impl->to = *to;
  error_code ec;
  impl->acceptor.open(listen->protocol(), ec);
  if (!ec) impl->acceptor.set_option(net::socket_base::reuse_address(true), ec);
  if (!ec) impl->acceptor.bind(*listen, ec);
  if (!ec) impl->acceptor.listen(net::socket_base::max_listen_connections, ec);
  if (!ec) impl->port = impl->acceptor.local_endpoint(ec).port();
  if (ec) {
    return absl::UnavailableError(
        absl::StrCat("cannot listen on ", options.listen, ": ", ec.message()));
  }
  impl->Accept();
  Impl* raw = impl.get();
  impl->thread = std::thread([raw] { raw->io.run(); });
  return std::unique_ptr<TcpRelay>(new TcpRelay(std::move(impl)));
}

TcpRelay::TcpRelay(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

TcpRelay::~TcpRelay() { Stop(); }

void TcpRelay::Stop() {
  if (!impl_->thread.joinable()) return;
  net::post(impl_->io, [impl = impl_.get()] {
    error_code ignored;
    impl->acceptor.close(ignored);
    for (const std::weak_ptr<Connection>& c : impl->connections) {
      if (std::shared_ptr<Connection> open = c.lock()) open->Close();
    }
    impl->io.stop();
  });
  impl_->thread.join();
}

uint16_t TcpRelay::port() const { return impl_->port; }

TcpRelay::Counters TcpRelay::counters() const {
  return {impl_->accepted.load(), impl_->bytes_up.load(), impl_->bytes_down.load(),
          impl_->stalls.load(), impl_->peak_in_flight.load()};
}

}  // namespace hs::cli
