#include "client/viewer/ws_admission.h"

#include <openssl/crypto.h>
#include <openssl/rand.h>

#include <algorithm>
#include <cctype>

namespace hs::cli {

namespace {

constexpr int kTokenBytes = 32;

bool SameIgnoringCase(std::string_view a, std::string_view b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](char x, char y) {
    return std::tolower(static_cast<unsigned char>(x)) ==
           std::tolower(static_cast<unsigned char>(y));
  });
}

}  // namespace

absl::StatusOr<std::string> NewViewToken() {
  unsigned char bytes[kTokenBytes];
  if (RAND_bytes(bytes, kTokenBytes) != 1) {
    return absl::InternalError("the system's random generator gave no bytes for the viewer token");
  }
  static constexpr char kHex[] = "0123456789abcdef";
  std::string token;
  for (const unsigned char byte : bytes) {
    token += kHex[byte >> 4];
    token += kHex[byte & 15];
  }
  return token;
}

std::string_view TokenInTarget(std::string_view target) {
  const size_t question = target.find('?');
  if (question == std::string_view::npos) return {};
  std::string_view query = target.substr(question + 1);
  query = query.substr(0, query.find('#'));
  while (!query.empty()) {
    const size_t amp = query.find('&');
    const std::string_view pair = query.substr(0, amp);
    if (pair.starts_with("token=")) return pair.substr(6);
    if (amp == std::string_view::npos) break;
    query.remove_prefix(amp + 1);
  }
  return {};
}

WsAdmission::WsAdmission(std::string token, bool tls)
    : token_(std::move(token)), scheme_(tls ? "https" : "http") {}

absl::Status WsAdmission::CheckToken(std::string_view target) const {
  const std::string_view given = TokenInTarget(target);
  if (given.empty()) return absl::PermissionDeniedError("no viewer token");
  // The length is no secret (every token has the same); the bytes are
  // compared in a time that does not depend on where they differ.
  if (given.size() != token_.size() ||
      CRYPTO_memcmp(given.data(), token_.data(), token_.size()) != 0) {
    return absl::PermissionDeniedError("wrong viewer token");
  }
  return absl::OkStatus();
}

absl::Status WsAdmission::Admit(std::string_view origin, std::string_view host,
                                std::string_view target) const {
  if (origin.empty()) return absl::PermissionDeniedError("no Origin");
  if (host.empty()) return absl::PermissionDeniedError("no Host");
  // Browsers send the origin in lowercase; a Host is as the user typed it.
  const std::string own = scheme_ + "://" + std::string(host);
  if (!SameIgnoringCase(origin, own)) {
    return absl::PermissionDeniedError("Origin " + std::string(origin) + " is not the page's (" +
                                       own + ")");
  }
  return CheckToken(target);
}

}  // namespace hs::cli
