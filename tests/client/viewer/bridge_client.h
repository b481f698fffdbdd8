#pragma once
// A test's side of the viewer bridge: GET requests and one page's
// WebSocket on 127.0.0.1, over TLS (trusting a CA file) or not.

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>

namespace hs::cli::testing {

struct HttpReply {
  int status = 0;                              // 0: no answer
  std::map<std::string, std::string> headers;  // names in lowercase
  std::string body;
};

/// GET `target` from 127.0.0.1:`port`; over TLS when `ca` is given.
HttpReply Get(uint16_t port, const std::string& target, const std::filesystem::path& ca = {});

class PageClient {
 public:
  /// Asks 127.0.0.1:`port` to upgrade `target` to a WebSocket, sending
  /// `origin` ("" for no Origin header); over TLS when `ca` is given.
  PageClient(uint16_t port, const std::string& origin, const std::string& target,
             const std::filesystem::path& ca = {});
  ~PageClient();

  /// The answer's HTTP status: 101 when the socket is open.
  int status() const;
  /// The next text message ("" once the socket ended).
  std::string Read();
  void Write(const std::string& text);

  struct Socket;

 private:
  std::unique_ptr<Socket> socket_;
};

}  // namespace hs::cli::testing
