#include "server/auth/token_table.h"

#include <fstream>
#include <sstream>
#include <vector>

#include "absl/strings/ascii.h"
#include "absl/strings/escaping.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "common/hash/sha256.h"

namespace hs {
namespace {

std::string HexSha256(absl::string_view bytes) {
  Sha256 hash;
  hash.Update(std::string_view(bytes.data(), bytes.size()));
  return absl::BytesToHexString(hash.Finish());
}

// 1 to 64 letters, digits and . _ @ -: safe in frames, logs and labels.
bool IsHolderName(absl::string_view s) {
  if (s.empty() || s.size() > 64) return false;
  for (char c : s) {
    if (!absl::ascii_isalnum(c) && c != '.' && c != '_' && c != '@' && c != '-') return false;
  }
  return true;
}

bool IsLowerHex(absl::string_view s) {
  for (char c : s) {
    if (!absl::ascii_isdigit(c) && !(c >= 'a' && c <= 'f')) return false;
  }
  return true;
}

}  // namespace

absl::string_view RoleName(Role role) {
  switch (role) {
    case Role::kAdmin:
      return "admin";
    case Role::kDrive:
      return "drive";
    case Role::kWatch:
      return "watch";
  }
  return "?";
}

absl::StatusOr<TokenTable> TokenTable::Parse(absl::string_view text, absl::string_view source) {
  TokenTable table;
  int line_number = 0;
  for (absl::string_view line : absl::StrSplit(text, '\n')) {
    ++line_number;
    auto error = [&](absl::string_view what) {
      return absl::InvalidArgumentError(absl::StrCat(source, ":", line_number, ": ", what));
    };
    line = absl::StripAsciiWhitespace(line);
    if (line.empty() || line.front() == '#') continue;
    const std::vector<absl::string_view> fields =
        absl::StrSplit(line, absl::ByAnyChar(" \t"), absl::SkipEmpty());
    if (fields.size() != 3 && fields.size() != 4) {
      return error("expected 'sha256:<hex> ROLE SCENE_PATTERN [NAME]'");
    }
    std::string digest = absl::AsciiStrToLower(fields[0]);
    if (!absl::StartsWith(digest, "sha256:") || digest.size() != 7 + 64 ||
        !IsLowerHex(absl::string_view(digest).substr(7))) {
      return error("the token must be given as sha256: and 64 hex digits");
    }
    digest.erase(0, 7);
    Grant grant;
    if (fields[1] == "admin") {
      grant.role = Role::kAdmin;
    } else if (fields[1] == "drive") {
      grant.role = Role::kDrive;
    } else if (fields[1] == "watch") {
      grant.role = Role::kWatch;
    } else {
      return error(absl::StrCat("unknown role '", fields[1], "' (admin, drive, watch)"));
    }
    grant.scene_pattern = std::string(fields[2]);
    grant.caller = absl::StrCat("token:", digest.substr(0, 12));
    grant.name = grant.caller;
    if (fields.size() == 4) {
      if (!IsHolderName(fields[3])) {
        return error("NAME must be 1 to 64 letters, digits and . _ @ -");
      }
      grant.name = std::string(fields[3]);
    }
    if (!table.by_digest_.emplace(digest, std::move(grant)).second) {
      return error("this token is listed twice");
    }
  }
  return table;
}

absl::StatusOr<TokenTable> TokenTable::Read(const std::string& path) {
  std::ifstream in(path);
  if (!in) return absl::InvalidArgumentError(absl::StrCat("cannot read ", path));
  std::ostringstream text;
  text << in.rdbuf();
  return Parse(text.str(), path);
}

const Grant* TokenTable::Find(absl::string_view token) const {
  const auto it = by_digest_.find(HexSha256(token));
  return it == by_digest_.end() ? nullptr : &it->second;
}

}  // namespace hs
