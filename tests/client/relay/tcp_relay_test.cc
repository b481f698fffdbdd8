#include "client/relay/tcp_relay.h"

#include <gtest/gtest.h>
#include <sys/socket.h>

#include <boost/asio.hpp>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "client/remote/link_schedule.h"

namespace hs::cli {
namespace {

namespace net = boost::asio;
using tcp = net::ip::tcp;
using Clock = std::chrono::steady_clock;
using boost::system::error_code;

// A server on a free 127.0.0.1 port that takes one connection, echoes
// what it reads and notes when each read arrived, and ends with it.
class EchoPeer {
 public:
  EchoPeer() : acceptor_(io_, tcp::endpoint(net::ip::make_address("127.0.0.1"), 0)) {
    thread_ = std::thread([this] {
      tcp::socket socket(io_);
      error_code ec;
      acceptor_.accept(socket, ec);
      std::vector<char> buffer(64 << 10);
      while (!ec) {
        const size_t n = socket.read_some(net::buffer(buffer), ec);
        if (ec) break;
        {
          std::lock_guard lock(mutex_);
          arrivals_.push_back({Clock::now(), n});
        }
        net::write(socket, net::buffer(buffer.data(), n), ec);
      }
      socket.shutdown(tcp::socket::shutdown_send, ec);
    });
  }
  ~EchoPeer() {
    // Wakes an accept that never got its connection.
    ::shutdown(acceptor_.native_handle(), SHUT_RDWR);
    thread_.join();
  }

  std::string address() const {
    return "127.0.0.1:" + std::to_string(acceptor_.local_endpoint().port());
  }
  struct Arrival {
    Clock::time_point at;
    size_t bytes;
  };
  std::vector<Arrival> arrivals() {
    std::lock_guard lock(mutex_);
    return arrivals_;
  }

 private:
  net::io_context io_;
  tcp::acceptor acceptor_;
  std::thread thread_;
  std::mutex mutex_;
  std::vector<Arrival> arrivals_;
};

std::unique_ptr<TcpRelay> StartRelay(RelayOptions options) {
  absl::StatusOr<std::unique_ptr<TcpRelay>> relay = TcpRelay::Start(options);
  EXPECT_TRUE(relay.ok()) << relay.status();
  return relay.ok() ? *std::move(relay) : nullptr;
}

// A client connected to the relay.
struct Client {
  explicit Client(const TcpRelay& relay) : socket(io) {
    socket.connect(tcp::endpoint(net::ip::make_address("127.0.0.1"), relay.port()));
    socket.set_option(tcp::no_delay(true));
  }
  net::io_context io;
  tcp::socket socket;
};

// Sends `payload` through the relay to an echo peer and back, writing on
// one thread and reading on another, and returns what came back.
std::string EchoThrough(const RelayOptions& options, const std::string& payload,
                        TcpRelay::Counters* counters) {
  EchoPeer peer;
  RelayOptions with_peer = options;
  with_peer.to = peer.address();
  std::unique_ptr<TcpRelay> relay = StartRelay(with_peer);
  if (!relay) return "";
  Client client(*relay);
  std::thread writer([&] {
    error_code ec;
    net::write(client.socket, net::buffer(payload), ec);
    client.socket.shutdown(tcp::socket::shutdown_send, ec);
  });
  std::string back;
  std::vector<char> buffer(64 << 10);
  error_code ec;
  while (!ec) {
    const size_t n = client.socket.read_some(net::buffer(buffer), ec);
    back.append(buffer.data(), n);
  }
  writer.join();
  relay->Stop();
  *counters = relay->counters();
  return back;
}

std::string RandomPayload(size_t size) {
  std::mt19937_64 random(1);
  std::string payload(size, '\0');
  for (char& c : payload) c = static_cast<char>(random());
  return payload;
}

// 2 MiB of random bytes go through the relay to an echo server and back
// intact and in order, across jitter and stalls; each way carries them
// all, and no direction ever holds more than its cap.
TEST(TcpRelayTest, BytesArriveIntactAndInOrderBothWays) {
  const std::string payload = RandomPayload(2 << 20);
  TcpRelay::Counters counters;
  const std::string back = EchoThrough({.one_way_ms = 2,
                                        .jitter_ms = 2,
                                        .stall_prob = 0.05,
                                        .stall_ms = 5,
                                        .seed = 7,
                                        .max_in_flight_bytes = 64 << 10},
                                       payload, &counters);
  EXPECT_TRUE(back == payload) << back.size() << " of " << payload.size() << " bytes";
  EXPECT_EQ(counters.connections, 1);
  EXPECT_EQ(counters.bytes_up, static_cast<int64_t>(payload.size()));
  EXPECT_EQ(counters.bytes_down, static_cast<int64_t>(payload.size()));
  EXPECT_GT(counters.stalls, 0);
  EXPECT_LE(counters.peak_in_flight_bytes, 64 << 10);
}

// A byte's round trip through the relay takes at least the one-way
// latency twice (a lower bound: the relay holds each chunk that long).
TEST(TcpRelayTest, HoldsEachWayAtLeastTheOneWayLatency) {
  EchoPeer peer;
  std::unique_ptr<TcpRelay> relay = StartRelay({.to = peer.address(), .one_way_ms = 30});
  ASSERT_TRUE(relay);
  Client client(*relay);
  for (int i = 0; i < 3; ++i) {
    const Clock::time_point sent = Clock::now();
    net::write(client.socket, net::buffer("x", 1));
    char back = 0;
    net::read(client.socket, net::buffer(&back, 1));
    EXPECT_EQ(back, 'x');
    EXPECT_GE(Clock::now() - sent, std::chrono::milliseconds(60));
  }
}

// The first seed whose upward direction of the first connection stalls
// its first chunk and not its second (the relay's own schedule, as the
// oracle).
uint64_t SeedStallingOnlyTheFirst(const LinkConditions& link) {
  for (uint64_t seed = 1;; ++seed) {
    LinkConditions seeded = link;
    seeded.seed = seed;
    LinkSchedule up(seeded, 0);
    up.Release(0);
    const int64_t first = up.stalled();
    up.Release(0);
    if (first == 1 && up.stalled() == 1) return seed;
  }
}

// A stalled chunk holds the chunk sent after it: the second byte, sent
// 50 ms after the first and not stalled itself, reaches the server no
// earlier than the first byte's 200 ms stall ends.
TEST(TcpRelayTest, StallHoldsLaterChunks) {
  const uint64_t seed = SeedStallingOnlyTheFirst({.stall_prob = 0.5, .stall_ms = 200});
  EchoPeer peer;
  std::unique_ptr<TcpRelay> relay =
      StartRelay({.to = peer.address(), .stall_prob = 0.5, .stall_ms = 200, .seed = seed});
  ASSERT_TRUE(relay);
  Client client(*relay);
  const Clock::time_point first_sent = Clock::now();
  net::write(client.socket, net::buffer("a", 1));
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  net::write(client.socket, net::buffer("b", 1));
  char back[2] = {};
  net::read(client.socket, net::buffer(back, 2));
  EXPECT_EQ(std::string(back, 2), "ab");
  const std::vector<EchoPeer::Arrival> arrivals = peer.arrivals();
  ASSERT_FALSE(arrivals.empty());
  // The last arrival carries the second byte.
  EXPECT_GE(arrivals.back().at - first_sent, std::chrono::milliseconds(200));
}

// Addresses off loopback are refused unless allowed; bad values and
// malformed addresses are refused; nothing listens then.
TEST(TcpRelayTest, RefusesRemoteAddressesAndBadValues) {
  const auto code = [](const RelayOptions& options) {
    return TcpRelay::Start(options).status().code();
  };
  const std::string local = "127.0.0.1:9";
  EXPECT_EQ(code({.to = "10.1.2.3:80"}), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(code({.to = "example.com:80"}), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(code({.listen = "0.0.0.0:0", .to = local}), absl::StatusCode::kInvalidArgument);
  const absl::Status remote = TcpRelay::Start({.to = "10.1.2.3:80"}).status();
  EXPECT_NE(remote.message().find("--allow-remote"), std::string::npos) << remote;
  // Allowed, a remote destination is taken (nothing connects to it until a client comes).
  EXPECT_TRUE(TcpRelay::Start({.to = "10.1.2.3:80", .allow_remote = true}).ok());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const RelayOptions& bad :
       {RelayOptions{.to = local, .one_way_ms = -1}, RelayOptions{.to = local, .one_way_ms = nan},
        RelayOptions{.to = local, .jitter_ms = nan}, RelayOptions{.to = local, .stall_prob = 1.5},
        RelayOptions{.to = local, .stall_ms = -5},
        RelayOptions{.to = local, .max_in_flight_bytes = 100}, RelayOptions{.to = "nohost"},
        RelayOptions{.listen = "127.0.0.1:99999", .to = local}}) {
    EXPECT_EQ(code(bad), absl::StatusCode::kInvalidArgument) << bad.to << " " << bad.listen;
  }
}

}  // namespace
}  // namespace hs::cli
