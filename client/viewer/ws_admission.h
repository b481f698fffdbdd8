#pragma once
// Who may open the viewer bridge's WebSocket (docs/security.md, "The
// browser viewer"): a page of the bridge's own origin that knows the
// secret the bridge announced in its URL. A page of any other site the
// user has open reaches a loopback port too (cross-site WebSocket
// hijacking); the origin check stops it in the browser, the secret stops
// whoever is not a browser, or rebinds a name of their own to the
// bridge's address.

#include <string>
#include <string_view>

#include "absl/status/status.h"
#include "absl/status/statusor.h"

namespace hs::cli {

/// A new secret: 32 bytes from OpenSSL's CSPRNG as 64 lowercase hex
/// digits. INTERNAL when the generator has no entropy to give.
absl::StatusOr<std::string> NewViewToken();

/// The value of `token=` in the query of a request target ("" when none).
std::string_view TokenInTarget(std::string_view target);

class WsAdmission {
 public:
  /// `token`: the secret (never empty); `tls`: the page is served over
  /// https, so its origin is https://.
  WsAdmission(std::string token, bool tls);

  /// The secret a request must carry, for URLs the bridge announces.
  const std::string& token() const { return token_; }

  /// Whether a request for `target` names the secret, compared in
  /// constant time. PERMISSION_DENIED saying what is missing or wrong
  /// (never quoting either secret).
  absl::Status CheckToken(std::string_view target) const;

  /// A WebSocket upgrade: its Origin must be the page's own, the scheme
  /// and the Host the request was sent to, and its target must name the
  /// secret. PERMISSION_DENIED otherwise.
  absl::Status Admit(std::string_view origin, std::string_view host, std::string_view target) const;

 private:
  std::string token_;
  std::string scheme_;
};

}  // namespace hs::cli
