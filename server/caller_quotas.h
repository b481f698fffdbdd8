#pragma once
// Per-caller quotas: what one caller (a token, or a peer address on an open
// server; see Caller in auth/access_policy.h) may hold at once, so that no
// client can take every stream slot, fill the model store or make every
// scene. Server-wide limits (ServerLimits) still apply on top.

#include <map>
#include <mutex>
#include <string>
#include <utility>

#include "absl/status/status.h"

namespace hs {

/// What one caller may hold at once (RESOURCE_EXHAUSTED past these).
struct CallerLimits {
  /// Open Interact and Watch streams.
  int streams = 16;
  /// UploadModel streams in progress.
  int uploads_in_flight = 2;
  /// Stored models it uploaded (until deleted).
  int models = 32;
  /// Scenes it created (until deleted, by anyone).
  int scenes = 8;
};

enum class Quota { kStreams, kUploadsInFlight, kModels, kScenes };

/// Thread-safe.
class CallerQuotas {
 public:
  explicit CallerQuotas(const CallerLimits& limits) : limits_(limits) {}

  /// Takes one `quota` for `caller`. RESOURCE_EXHAUSTED naming the quota
  /// and its limit when the caller holds all it may.
  absl::Status Take(const std::string& caller, Quota quota);
  /// Gives back one `quota` that `caller` took.
  void Give(const std::string& caller, Quota quota);

  /// Records that the `quota` `caller` took is held by the thing named
  /// `key` (a scene name, a model id), so that Disown gives it back to
  /// `caller` whoever ends the thing.
  void Own(const std::string& caller, Quota quota, const std::string& key);
  /// Gives back the `quota` held by `key` to its owner, if it has one.
  void Disown(Quota quota, const std::string& key);

  /// How many `quota` `caller` holds.
  int held(const std::string& caller, Quota quota) const;

 private:
  int LimitOf(Quota quota) const;

  const CallerLimits limits_;
  mutable std::mutex mu_;
  std::map<std::pair<std::string, Quota>, int> held_;
  std::map<std::pair<Quota, std::string>, std::string> owners_;
};

}  // namespace hs
