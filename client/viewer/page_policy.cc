#include "client/viewer/page_policy.h"

#include "absl/strings/ascii.h"
#include "absl/strings/escaping.h"
#include "common/hash/sha256.h"

namespace hs::cli {

std::vector<std::string> InlineScriptHashes(std::string_view html) {
  std::vector<std::string> hashes;
  constexpr std::string_view kOpen = "<script", kClose = "</script>";
  for (size_t at = html.find(kOpen); at != std::string_view::npos; at = html.find(kOpen, at)) {
    const size_t tag_end = html.find('>', at);
    if (tag_end == std::string_view::npos) break;
    const size_t close = html.find(kClose, tag_end);
    if (close == std::string_view::npos) break;
    const std::string tag = absl::AsciiStrToLower(std::string(html.substr(at, tag_end - at)));
    if (tag.find(" src=") == std::string::npos) {
      const std::string_view text = html.substr(tag_end + 1, close - tag_end - 1);
      hashes.push_back("'sha256-" + absl::Base64Escape(Sha256Of(text)) + "'");
    }
    at = close + kClose.size();
  }
  return hashes;
}

std::string PageContentSecurityPolicy(std::string_view index_html) {
  const std::vector<std::string> hashes = InlineScriptHashes(index_html);
  std::string scripts = "'self'";
  for (const std::string& hash : hashes) scripts += " " + hash;
  return "default-src 'self'; script-src " + scripts +
         "; connect-src 'self'; img-src 'self' data:; style-src 'self'; object-src 'none'; "
         "base-uri 'none'; form-action 'none'; frame-ancestors 'none'";
}

std::vector<std::pair<std::string, std::string>> PageSecurityHeaders(std::string_view index_html) {
  return {{"Content-Security-Policy", PageContentSecurityPolicy(index_html)},
          {"X-Content-Type-Options", "nosniff"},
          {"Referrer-Policy", "no-referrer"}};
}

}  // namespace hs::cli
