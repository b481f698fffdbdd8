#pragma once
// SHA-256 of a byte stream: uploaded models, tokens, recorded frames.
// OpenSSL (libssl-dev, which gRPC already depends on) has a fast one.

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

namespace hs {

/// Incremental SHA-256.
class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;

  /// Adds the next bytes.
  void Update(std::string_view bytes);
  /// The digest of every byte added (32 bytes); call once.
  std::string Finish();

 private:
  struct Context;
  std::unique_ptr<Context> context_;
};

/// The SHA-256 digest of `bytes` (32 bytes).
std::string Sha256Of(std::string_view bytes);

}  // namespace hs
