#pragma once
// The viewer bridge's web side (Boost.Beast: HTTP and WebSocket in one
// header-only library that Debian packages, so no server of our own to
// write): serves the page and three.js (web_assets.h), GET /geometry and
// GET /frame, and a WebSocket at /ws per page. Every 1/60 s the newest
// frame goes to each page, latest wins: a page still reading the last one
// gets the newest when it is done, the ones between counted as dropped, so
// a slow page never slows the scene or the other pages. A page's poses
// (page_message.h) drive a tool through its own Interact stream
// (page_device.h). One thread runs it all.
//
// Its edge (docs/security.md): it makes a secret at start and announces it
// in its URL; /geometry, /frame and the WebSocket need it, the WebSocket
// also the page's own Origin (ws_admission.h), and everything goes out
// with a policy that allows the bridge alone (page_policy.h). With a
// certificate and key it serves https:// and wss:// (OpenSSL).

#include <cstdint>
#include <memory>
#include <string>

#include "absl/status/statusor.h"
#include "client/viewer/scene_link.h"

namespace hs::cli {

struct ViewServerOptions {
  /// Where to listen; loopback unless told otherwise. Port 0: any free one.
  std::string host = "127.0.0.1";
  uint16_t port = 0;
  /// Frames sent to each page per second, at most.
  double send_hz = 60;
  /// PEM certificate (chain) and private key: serve over TLS. Both or
  /// neither.
  std::string tls_cert_file;
  std::string tls_key_file;
};

class ViewServer {
 public:
  /// Listens on options' address and serves `link`'s scene (which outlives
  /// the server). INVALID_ARGUMENT for a bad host, or TLS files that are
  /// missing, hold no PEM certificate or key, or do not match (naming the
  /// file); UNAVAILABLE when the address cannot be bound.
  static absl::StatusOr<std::unique_ptr<ViewServer>> Start(SceneLink& link,
                                                           const ViewServerOptions& options);
  ~ViewServer();

  /// The port it listens on.
  uint16_t port() const;
  /// The secret pages bring (64 hex digits, new at every start).
  const std::string& token() const;
  /// The page's address, secret included: http[s]://HOST:PORT/?token=...
  std::string url() const;

  struct Counters {
    int64_t pages = 0;              // WebSocket pages open now
    int64_t rejected_messages = 0;  // page messages dropped at the edge
    int64_t poses_forwarded = 0;
  };
  Counters counters() const;

  struct Impl;

 private:
  explicit ViewServer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace hs::cli
