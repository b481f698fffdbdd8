#include "client/loadtest/metrics_scrape.h"

#include <curl/curl.h>

#include <memory>

#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"

namespace hs::cli {
namespace {

// curl_global_init is not thread-safe: once, before any request.
void InitCurl() {
  static const CURLcode init = curl_global_init(CURL_GLOBAL_DEFAULT);
  (void)init;
}

size_t AppendBody(char* data, size_t size, size_t count, void* body) {
  static_cast<std::string*>(body)->append(data, size * count);
  return size * count;
}

}  // namespace

absl::Status CheckMetricsUrl(const std::string& url) {
  const absl::Status bad = absl::InvalidArgumentError(
      "--server-metrics must be http://HOST:PORT/PATH (e.g. http://127.0.0.1:9464/metrics), not '" +
      url + "'");
  constexpr absl::string_view kScheme = "http://";
  if (!absl::StartsWith(url, kScheme)) return bad;
  const std::string authority =
      url.substr(kScheme.size(), url.find('/', kScheme.size()) - kScheme.size());
  const size_t colon = authority.rfind(':');
  int port = 0;
  if (colon == std::string::npos || colon == 0 ||
      !absl::SimpleAtoi(authority.substr(colon + 1), &port) || port < 1 || port > 65535) {
    return bad;
  }
  return absl::OkStatus();
}

absl::StatusOr<std::string> FetchMetricsText(const std::string& url, double timeout_s) {
  InitCurl();
  const std::unique_ptr<CURL, decltype(&curl_easy_cleanup)> get(curl_easy_init(),
                                                                curl_easy_cleanup);
  if (!get) return absl::UnavailableError("GET " + url + ": no curl handle");
  std::string body;
  curl_easy_setopt(get.get(), CURLOPT_URL, url.c_str());
  curl_easy_setopt(get.get(), CURLOPT_TIMEOUT_MS, static_cast<long>(timeout_s * 1e3));
  curl_easy_setopt(get.get(), CURLOPT_NOSIGNAL, 1L);  // timeouts without SIGALRM, in threads
  curl_easy_setopt(get.get(), CURLOPT_WRITEFUNCTION, AppendBody);
  curl_easy_setopt(get.get(), CURLOPT_WRITEDATA, &body);
  if (const CURLcode code = curl_easy_perform(get.get()); code != CURLE_OK) {
    return absl::UnavailableError(absl::StrCat("GET ", url, ": ", curl_easy_strerror(code)));
  }
  long http = 0;
  curl_easy_getinfo(get.get(), CURLINFO_RESPONSE_CODE, &http);
  if (http != 200) return absl::UnavailableError(absl::StrCat("GET ", url, ": HTTP ", http));
  return body;
}

}  // namespace hs::cli
