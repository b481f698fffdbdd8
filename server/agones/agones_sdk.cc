#include "server/agones/agones_sdk.h"

#include <curl/curl.h>

#include <cctype>
#include <memory>

#include "absl/strings/str_cat.h"
#include "nlohmann/json.hpp"

namespace hs {
namespace {

// Once per process, before any thread uses curl (curl_global_init is not
// thread-safe).
void InitCurlOnce() {
  static const bool done = [] { return curl_global_init(CURL_GLOBAL_DEFAULT) == CURLE_OK; }();
  (void)done;
}

size_t DiscardBody(char*, size_t size, size_t count, void*) { return size * count; }

}  // namespace

AgonesSdk::AgonesSdk(int port, double timeout_s)
    : base_url_(absl::StrCat("http://127.0.0.1:", port)),
      timeout_ms_(static_cast<long>(timeout_s * 1000)) {
  InitCurlOnce();
}

absl::Status AgonesSdk::Ready() { return Request("POST", "/ready", "{}"); }
absl::Status AgonesSdk::Health() { return Request("POST", "/health", "{}"); }
absl::Status AgonesSdk::Allocate() { return Request("POST", "/allocate", "{}"); }
absl::Status AgonesSdk::Shutdown() { return Request("POST", "/shutdown", "{}"); }

absl::Status AgonesSdk::SetLabel(std::string_view key, std::string_view value) {
  const nlohmann::json body = {{"key", key}, {"value", value}};
  return Request("PUT", "/metadata/label", body.dump());
}

absl::Status AgonesSdk::Request(const char* method, const char* path, const std::string& body) {
  const std::unique_ptr<CURL, decltype(&curl_easy_cleanup)> curl(curl_easy_init(),
                                                                 curl_easy_cleanup);
  if (!curl) return absl::UnavailableError(absl::StrCat(method, " ", path, ": no curl handle"));
  const std::unique_ptr<curl_slist, decltype(&curl_slist_free_all)> headers(
      curl_slist_append(nullptr, "Content-Type: application/json"), curl_slist_free_all);
  const std::string url = base_url_ + path;
  curl_easy_setopt(curl.get(), CURLOPT_URL, url.c_str());
  curl_easy_setopt(curl.get(), CURLOPT_CUSTOMREQUEST, method);
  curl_easy_setopt(curl.get(), CURLOPT_HTTPHEADER, headers.get());
  curl_easy_setopt(curl.get(), CURLOPT_POSTFIELDS, body.c_str());
  curl_easy_setopt(curl.get(), CURLOPT_POSTFIELDSIZE, static_cast<long>(body.size()));
  curl_easy_setopt(curl.get(), CURLOPT_TIMEOUT_MS, timeout_ms_);
  curl_easy_setopt(curl.get(), CURLOPT_NOSIGNAL, 1L);  // timeouts without SIGALRM, in threads
  curl_easy_setopt(curl.get(), CURLOPT_WRITEFUNCTION, DiscardBody);
  const CURLcode code = curl_easy_perform(curl.get());
  if (code != CURLE_OK) {
    return absl::UnavailableError(absl::StrCat(method, " ", url, ": ", curl_easy_strerror(code)));
  }
  long http = 0;
  curl_easy_getinfo(curl.get(), CURLINFO_RESPONSE_CODE, &http);
  if (http < 200 || http >= 300) {
    return absl::UnavailableError(absl::StrCat(method, " ", url, ": HTTP ", http));
  }
  return absl::OkStatus();
}

std::string AgonesLabelValue(std::string_view text) {
  auto alnum = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0; };
  std::string value;
  for (const char c : text) {
    const char lower = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (alnum(lower) || lower == '.' || lower == '_' || lower == '-') {
      value += lower;
    } else if (value.empty() || value.back() != '-') {
      value += '-';
    }
  }
  if (value.size() > 63) value.resize(63);
  while (!value.empty() && !alnum(value.back())) value.pop_back();
  size_t first = 0;
  while (first < value.size() && !alnum(value[first])) ++first;
  return value.substr(first);
}

}  // namespace hs
