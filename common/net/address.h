#pragma once
// What server and client both need to know of a gRPC address.

#include <string_view>

namespace hs {

/// True when `address` (host:port, [v6]:port, ipv4:host:port or unix:path)
/// can be reached from this machine only: 127.x.x.x, localhost, [::1] or a
/// Unix socket.
bool IsLoopbackAddress(std::string_view address);

}  // namespace hs
