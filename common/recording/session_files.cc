#include "common/recording/session_files.h"

#include <ctime>
#include <filesystem>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_replace.h"

namespace hs {
namespace {

constexpr char kSuffix[] = ".hsrec";
constexpr size_t kSuffixBytes = 6;
constexpr size_t kPartDigits = 3;

}  // namespace

std::string SessionFileName(const std::string& scene, int64_t start_unix_ns, int part) {
  const time_t seconds = static_cast<time_t>(start_unix_ns / 1'000'000'000);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%dT%H%M%S", &utc);
  return absl::StrFormat("%s_%s.%03dZ.%03d%s", absl::StrReplaceAll(scene, {{" ", "_"}}), stamp,
                         static_cast<int>((start_unix_ns / 1'000'000) % 1000), part, kSuffix);
}

std::vector<std::string> SessionParts(const std::string& file) {
  std::vector<std::string> parts = {file};
  // "<stem>.NNN.hsrec"
  if (file.size() < kSuffixBytes + kPartDigits + 1 || !file.ends_with(kSuffix)) return parts;
  const size_t digits_at = file.size() - kSuffixBytes - kPartDigits;
  int part = 0;
  if (file[digits_at - 1] != '.' || !absl::SimpleAtoi(file.substr(digits_at, kPartDigits), &part)) {
    return parts;
  }
  const std::string stem = file.substr(0, digits_at);
  for (int next = part + 1;; ++next) {
    std::string name = absl::StrFormat("%s%03d%s", stem, next, kSuffix);
    std::error_code error;
    if (!std::filesystem::exists(name, error)) break;
    parts.push_back(std::move(name));
  }
  return parts;
}

}  // namespace hs
