#pragma once
// Who may call what: every call's bearer token (or, on an open server, its
// peer) becomes a Caller, and each call is checked against the caller's
// role and scene pattern.
//
// Roles, each allowing what the one before allows:
//   watch: GetScene, GetGeometry, ListScenes (only the scenes it may see)
//   and Watch
//   drive: and Interact (driving a tool)
//   admin: and every change: CreateScene, DeleteScene, AddObject,
//          UpdateObject, RemoveObject, SetEffects, UploadModel
// A scene-scoped call also needs the scene's name to match the caller's
// pattern. Health checks and reflection need no token.

#include <grpcpp/server_context.h>

#include <memory>
#include <mutex>
#include <string>
#include "absl/strings/string_view.h"

#include "absl/status/statusor.h"
#include "server/auth/token_table.h"

namespace hs {

/// What a call does, as far as access goes.
enum class Access {
  kRead,   ///< GetScene, GetGeometry, ListScenes
  kWatch,  ///< Watch
  kDrive,  ///< Interact
  kAdmin,  ///< changes to scenes and models
};

/// Who makes a call and what they may do.
struct Caller {
  /// "token:<12 hex digits of its SHA-256>", or "peer:<address>" on an open
  /// server; the key of per-caller quotas.
  std::string id;
  /// Who the caller is as viewers see it: the token's NAME
  /// (token_table.h), else `id`.
  std::string name;
  Role role = Role::kAdmin;
  std::string scene_pattern = "*";
};

class AccessPolicy {
 public:
  /// An open server: every caller is an admin of every scene, named by
  /// its peer address.
  AccessPolicy() = default;
  /// Checks tokens against `tokens_file`. Errors as TokenTable::Read.
  static absl::StatusOr<std::unique_ptr<AccessPolicy>> FromFile(const std::string& tokens_file);

  /// No tokens file: anyone may do anything.
  bool open() const { return tokens_file_.empty(); }
  /// Re-reads the tokens file and returns how many tokens it holds; on an
  /// error the tokens read before stay in force.
  absl::StatusOr<size_t> Reload();

  /// The caller of the call, when it may do `access` on scene `scene`
  /// (empty for calls that name none). UNAUTHENTICATED without an
  /// "authorization: Bearer TOKEN" header or with a token not in the file;
  /// PERMISSION_DENIED when the role or the scene pattern does not allow it.
  absl::StatusOr<Caller> Check(const grpc::ServerContextBase& context, Access access,
                               absl::string_view scene) const;
  /// Whether `caller` may see scene `scene` at all.
  static bool MaySee(const Caller& caller, absl::string_view scene);

 private:
  absl::StatusOr<Caller> Authenticate(const grpc::ServerContextBase& context) const;

  std::string tokens_file_;
  mutable std::mutex mu_;
  std::shared_ptr<const TokenTable> tokens_;  // swapped whole by Reload
};

}  // namespace hs
