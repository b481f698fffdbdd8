#pragma once
// What server and client both need to know of a gRPC address.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace hs {

/// True when `address` (host:port, [v6]:port, ipv4:host:port or unix:path)
/// can be reached from this machine only: 127.x.x.x, localhost, [::1] or a
/// Unix socket.
bool IsLoopbackAddress(std::string_view address);

struct HostPort {
  std::string host;
  uint16_t port = 0;
};

/// "host:port" or "[v6 address]:port" split, the brackets dropped; nullopt
/// without a host, without a port or with one past 65535.
std::optional<HostPort> SplitHostPort(std::string_view address);

}  // namespace hs
