#pragma once
// The tokens haptic-server accepts (--tokens FILE) and what each may do.
// The file holds one token a line, as its SHA-256, never the token itself:
//
//   # comment
//   sha256:<64 hex digits of SHA-256(token)> ROLE SCENE_PATTERN [NAME]
//
// ROLE is admin, drive or watch (access_policy.h says what each may call);
// SCENE_PATTERN is a shell glob (fnmatch) over scene names: `*` for all;
// NAME, optional, is who holds the token as viewers see it (frames name
// each tool's holder): 1 to 64 letters, digits and . _ @ -.
// `printf %s "$TOKEN" | sha256sum` makes the digest.

#include <map>
#include <string>
#include "absl/strings/string_view.h"

#include "absl/status/statusor.h"

namespace hs {

enum class Role { kWatch, kDrive, kAdmin };

/// "watch", "drive", "admin".
absl::string_view RoleName(Role role);

/// What one token may do.
struct Grant {
  Role role = Role::kWatch;
  std::string scene_pattern;
  /// "token:" and the first 12 hex digits of the token's SHA-256: names
  /// the caller in quotas and logs without revealing the token.
  std::string caller;
  /// The file's NAME, else `caller`.
  std::string name;
};

class TokenTable {
 public:
  /// Parses the file's text. INVALID_ARGUMENT naming `source` and the line
  /// for a malformed line, an unknown role or a digest given twice.
  static absl::StatusOr<TokenTable> Parse(absl::string_view text, absl::string_view source);
  /// Reads and parses `path`. INVALID_ARGUMENT when it cannot be read.
  static absl::StatusOr<TokenTable> Read(const std::string& path);

  /// The grant of `token` (the bearer token as sent), or nullptr.
  const Grant* Find(absl::string_view token) const;
  size_t size() const { return by_digest_.size(); }

 private:
  std::map<std::string, Grant> by_digest_;  // lower-case hex SHA-256
};

}  // namespace hs
