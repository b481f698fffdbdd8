#include "server/auth/access_policy.h"

#include <fnmatch.h>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/strip.h"

namespace hs {
namespace {

Role LeastRoleFor(Access access) {
  switch (access) {
    case Access::kRead:
    case Access::kWatch:
      return Role::kWatch;
    case Access::kDrive:
      return Role::kDrive;
    case Access::kAdmin:
      return Role::kAdmin;
  }
  return Role::kAdmin;
}

absl::string_view Doing(Access access) {
  switch (access) {
    case Access::kRead:
      return "read scenes";
    case Access::kWatch:
      return "watch scenes";
    case Access::kDrive:
      return "drive tools";
    case Access::kAdmin:
      return "change scenes or models";
  }
  return "?";
}

// "ipv4:127.0.0.1:5555" -> "127.0.0.1"; "ipv6:[::1]:5555" -> "[::1]": a
// client's connections share one caller, whatever their ports.
std::string PeerHost(std::string peer) {
  const size_t colon = peer.rfind(':');
  if (colon != std::string::npos && colon > peer.find(':')) peer.erase(colon);
  for (absl::string_view scheme : {"ipv4:", "ipv6:"}) {
    if (absl::StartsWith(peer, scheme)) peer.erase(0, scheme.size());
  }
  return peer;
}

}  // namespace

absl::StatusOr<std::unique_ptr<AccessPolicy>> AccessPolicy::FromFile(
    const std::string& tokens_file) {
  auto policy = std::make_unique<AccessPolicy>();
  policy->tokens_file_ = tokens_file;
  absl::StatusOr<size_t> read = policy->Reload();
  if (!read.ok()) return read.status();
  return policy;
}

absl::StatusOr<size_t> AccessPolicy::Reload() {
  if (open()) return 0;
  absl::StatusOr<TokenTable> table = TokenTable::Read(tokens_file_);
  if (!table.ok()) return table.status();
  const size_t count = table->size();
  auto tokens = std::make_shared<const TokenTable>(*std::move(table));
  std::lock_guard lock(mu_);
  tokens_ = std::move(tokens);
  return count;
}

absl::StatusOr<Caller> AccessPolicy::Authenticate(const grpc::ServerContextBase& context) const {
  if (open()) {
    std::string peer = "peer:" + PeerHost(context.peer());
    return Caller{.id = peer, .name = peer};
  }
  const auto& metadata = context.client_metadata();
  const auto header = metadata.find("authorization");
  if (header == metadata.end()) {
    return absl::UnauthenticatedError("this server needs a token (authorization: Bearer TOKEN)");
  }
  absl::string_view value(header->second.data(), header->second.size());
  if (!absl::ConsumePrefix(&value, "Bearer ")) {
    return absl::UnauthenticatedError("the authorization header must be 'Bearer TOKEN'");
  }
  std::shared_ptr<const TokenTable> tokens;
  {
    std::lock_guard lock(mu_);
    tokens = tokens_;
  }
  const Grant* grant = tokens->Find(value);
  if (grant == nullptr) return absl::UnauthenticatedError("unknown token");
  return Caller{.id = grant->caller,
                .name = grant->name,
                .role = grant->role,
                .scene_pattern = grant->scene_pattern};
}

absl::StatusOr<Caller> AccessPolicy::Check(const grpc::ServerContextBase& context, Access access,
                                           absl::string_view scene) const {
  absl::StatusOr<Caller> caller = Authenticate(context);
  if (!caller.ok()) return caller.status();
  if (caller->role < LeastRoleFor(access)) {
    return absl::PermissionDeniedError(
        absl::StrCat("role '", RoleName(caller->role), "' may not ", Doing(access)));
  }
  if (!scene.empty() && !MaySee(*caller, scene)) {
    return absl::PermissionDeniedError(absl::StrCat(
        "scene '", scene, "' is not among this token's scenes ('", caller->scene_pattern, "')"));
  }
  return caller;
}

bool AccessPolicy::MaySee(const Caller& caller, absl::string_view scene) {
  return fnmatch(caller.scene_pattern.c_str(), std::string(scene).c_str(), 0) == 0;
}

}  // namespace hs
