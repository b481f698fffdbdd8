#include "server/caller_quotas.h"

#include "absl/strings/str_cat.h"

namespace hs {
namespace {

const char* QuotaName(Quota quota) {
  switch (quota) {
    case Quota::kStreams:
      return "open streams";
    case Quota::kUploadsInFlight:
      return "uploads in progress";
    case Quota::kModels:
      return "stored models";
    case Quota::kScenes:
      return "scenes";
  }
  return "?";
}

}  // namespace

int CallerQuotas::LimitOf(Quota quota) const {
  switch (quota) {
    case Quota::kStreams:
      return limits_.streams;
    case Quota::kUploadsInFlight:
      return limits_.uploads_in_flight;
    case Quota::kModels:
      return limits_.models;
    case Quota::kScenes:
      return limits_.scenes;
  }
  return 0;
}

absl::Status CallerQuotas::Take(const std::string& caller, Quota quota) {
  std::lock_guard lock(mu_);
  int& held = held_[{caller, quota}];
  if (held >= LimitOf(quota)) {
    return absl::ResourceExhaustedError(
        absl::StrCat("at most ", LimitOf(quota), " ", QuotaName(quota), " per caller"));
  }
  ++held;
  return absl::OkStatus();
}

void CallerQuotas::Give(const std::string& caller, Quota quota) {
  std::lock_guard lock(mu_);
  const auto it = held_.find({caller, quota});
  if (it == held_.end()) return;
  if (--it->second <= 0) held_.erase(it);
}

void CallerQuotas::Own(const std::string& caller, Quota quota, const std::string& key) {
  std::lock_guard lock(mu_);
  owners_[{quota, key}] = caller;
}

void CallerQuotas::Disown(Quota quota, const std::string& key) {
  std::string owner;
  {
    std::lock_guard lock(mu_);
    const auto it = owners_.find({quota, key});
    if (it == owners_.end()) return;
    owner = std::move(it->second);
    owners_.erase(it);
  }
  Give(owner, quota);
}

int CallerQuotas::held(const std::string& caller, Quota quota) const {
  std::lock_guard lock(mu_);
  const auto it = held_.find({caller, quota});
  return it == held_.end() ? 0 : it->second;
}

}  // namespace hs
