#pragma once
// A TCP relay that makes a real connection behave like a long, uneven one:
// it accepts on one address, connects each client to another, and forwards
// the bytes both ways, each chunk it reads held the one-way latency plus a
// uniform jitter, sometimes stalled with everything behind it (a stream
// waiting for a lost segment), never reordered (link_schedule.h). Each
// connection has its own two directions, each seeded from the relay's seed
// and the connection's number. A direction holds at most
// max_in_flight_bytes and stops reading beyond it, so a fast sender meets
// TCP's own backpressure. One thread runs it all (Boost.Asio).

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "absl/status/statusor.h"

namespace hs::cli {

struct RelayOptions {
  /// HOST:PORT to accept on (port 0: any free one) and to connect to.
  std::string listen = "127.0.0.1:0";
  std::string to{};
  /// Each chunk is held this long each way, plus up to jitter_ms
  /// (uniformly), milliseconds.
  double one_way_ms = 0;
  double jitter_ms = 0;
  /// A chunk is held stall_ms longer with this probability, with the ones
  /// behind it.
  double stall_prob = 0;
  double stall_ms = 0;
  uint64_t seed = 1;
  /// Addresses off this machine's loopback are refused unless set.
  bool allow_remote = false;
  /// Bytes read and not yet written, per direction, with each chunk's
  /// bookkeeping, before it stops reading.
  size_t max_in_flight_bytes = 1 << 20;
};

class TcpRelay {
 public:
  /// Listens and starts relaying. INVALID_ARGUMENT for a value out of
  /// range, an address that is not HOST:PORT or does not resolve, or one
  /// off loopback without allow_remote; UNAVAILABLE when the listening
  /// address cannot be bound.
  static absl::StatusOr<std::unique_ptr<TcpRelay>> Start(const RelayOptions& options);
  /// Stops.
  ~TcpRelay();
  TcpRelay(const TcpRelay&) = delete;
  TcpRelay& operator=(const TcpRelay&) = delete;

  /// Stops accepting and closes every connection; returns when the relay's
  /// thread has ended. Idempotent.
  void Stop();

  /// The port it accepts on.
  uint16_t port() const;

  struct Counters {
    int64_t connections = 0;
    /// Bytes written to the `to` side and back to the clients.
    int64_t bytes_up = 0;
    int64_t bytes_down = 0;
    /// Chunks stalled, both ways.
    int64_t stalls = 0;
    /// The most bytes any one direction held at once.
    int64_t peak_in_flight_bytes = 0;
  };
  Counters counters() const;

  struct Impl;

 private:
  explicit TcpRelay(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace hs::cli
