// The viewer page's policy allows the bridge alone: its inline scripts by
// the hash a browser computes, nothing else inline, no framing.

#include "client/viewer/page_policy.h"

#include <gtest/gtest.h>

#include "absl/strings/match.h"

namespace hs::cli {
namespace {

// The hash of an inline script is of its exact text; scripts with a src
// have none. The oracles: `printf %s TEXT | openssl dgst -sha256 -binary |
// base64`.
TEST(PagePolicyTest, HashesTheTextOfInlineScriptsOnly) {
  const std::string html =
      "<head><script type=\"module\" src=\"viewer.js\"></script>"
      "<script>alert(1)</script><script type=\"importmap\">{\"a\":1}</script></head>";
  const std::vector<std::string> hashes = InlineScriptHashes(html);
  ASSERT_EQ(hashes.size(), 2u);
  EXPECT_EQ(hashes[0], "'sha256-bhHHL3z2vDgxUt0W3dWQOrprscmda2Y5pLsLg4GF+pI='");
  EXPECT_EQ(hashes[1], "'sha256-AVq9f1zFei3ZS3WQ8ErYCEJzkF7jPsXOvq5iJ2qX+GI='");
}

// The policy names the defaults, the hashes, and forbids framing.
TEST(PagePolicyTest, PolicyAllowsOnlySelf) {
  const std::string csp = PageContentSecurityPolicy("<script>alert(1)</script>");
  for (const char* part :
       {"default-src 'self'",
        "script-src 'self' 'sha256-bhHHL3z2vDgxUt0W3dWQOrprscmda2Y5pLsLg4GF+pI='",
        "connect-src 'self'", "frame-ancestors 'none'", "object-src 'none'"}) {
    EXPECT_TRUE(absl::StrContains(csp, part)) << part << " not in " << csp;
  }
  EXPECT_FALSE(absl::StrContains(csp, "unsafe"));
  const auto headers = PageSecurityHeaders("");
  EXPECT_EQ(headers.size(), 3u);
  EXPECT_EQ(headers[1], (std::pair<std::string, std::string>{"X-Content-Type-Options", "nosniff"}));
}

}  // namespace
}  // namespace hs::cli
