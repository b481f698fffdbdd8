// Who may open the viewer bridge's WebSocket: a page of the bridge's own
// origin with the secret the bridge made; everyone else is refused with a
// reason that never quotes a secret.

#include "client/viewer/ws_admission.h"

#include <gtest/gtest.h>

#include <set>

#include "absl/strings/match.h"

namespace hs::cli {
namespace {

std::string Token() {
  absl::StatusOr<std::string> token = NewViewToken();
  EXPECT_TRUE(token.ok()) << token.status();
  return token.value_or("");
}

// A token is 256 bits as 64 lowercase hex digits, new each time.
TEST(WsAdmissionTest, TokensAreLongHexAndFresh) {
  std::set<std::string> seen;
  for (int i = 0; i < 100; ++i) {
    const std::string token = Token();
    ASSERT_EQ(token.size(), 64u);
    EXPECT_EQ(token.find_first_not_of("0123456789abcdef"), std::string::npos) << token;
    seen.insert(token);
  }
  EXPECT_EQ(seen.size(), 100u);
}

// The token is the value of token= wherever it stands in the query, and
// nothing outside the query.
TEST(WsAdmissionTest, FindsTheTokenInTheQuery) {
  EXPECT_EQ(TokenInTarget("/ws?token=abc"), "abc");
  EXPECT_EQ(TokenInTarget("/ws?snapshot=1&token=abc&x=2"), "abc");
  EXPECT_EQ(TokenInTarget("/ws?token=abc#frag"), "abc");
  EXPECT_EQ(TokenInTarget("/ws"), "");
  EXPECT_EQ(TokenInTarget("/ws?token="), "");
  EXPECT_EQ(TokenInTarget("/ws?mytoken=abc"), "");
  EXPECT_EQ(TokenInTarget("/token=abc"), "");
}

// Only the whole secret passes: not a prefix, not a longer string, not
// one digit changed, not none.
TEST(WsAdmissionTest, OnlyTheExactTokenPasses) {
  const std::string token = Token();
  const WsAdmission admission(token, /*tls=*/false);
  EXPECT_TRUE(admission.CheckToken("/frame?token=" + token).ok());
  std::string changed = token;
  changed.back() = changed.back() == '0' ? '1' : '0';
  for (const std::string& target :
       std::vector<std::string>{"/frame", "/frame?token=", "/frame?token=" + token.substr(0, 63),
                                "/frame?token=" + token + "0", "/frame?token=" + changed}) {
    const absl::Status status = admission.CheckToken(target);
    EXPECT_EQ(status.code(), absl::StatusCode::kPermissionDenied) << target;
    EXPECT_FALSE(absl::StrContains(status.message(), token.substr(0, 8))) << status;
  }
}

// The Origin must be the scheme and Host the request came to (case aside);
// another port, host or scheme, "null" or none is refused even with the
// right token, and the right origin needs the token too.
TEST(WsAdmissionTest, OriginMustBeThePagesOwn) {
  const std::string token = Token();
  const std::string target = "/ws?token=" + token;
  const WsAdmission plain(token, /*tls=*/false);
  EXPECT_TRUE(plain.Admit("http://127.0.0.1:8080", "127.0.0.1:8080", target).ok());
  EXPECT_TRUE(plain.Admit("http://trainer-pc:8080", "Trainer-PC:8080", target).ok());
  EXPECT_TRUE(plain.Admit("http://[::1]:8080", "[::1]:8080", target).ok());
  for (const char* origin : {"http://evil.example", "http://127.0.0.1:8081", "http://127.0.0.1",
                             "https://127.0.0.1:8080", "null", ""}) {
    EXPECT_EQ(plain.Admit(origin, "127.0.0.1:8080", target).code(),
              absl::StatusCode::kPermissionDenied)
        << origin;
  }
  EXPECT_EQ(plain.Admit("http://127.0.0.1:8080", "", target).code(),
            absl::StatusCode::kPermissionDenied);
  EXPECT_EQ(plain.Admit("http://127.0.0.1:8080", "127.0.0.1:8080", "/ws").code(),
            absl::StatusCode::kPermissionDenied);
  const WsAdmission tls(token, /*tls=*/true);
  EXPECT_TRUE(tls.Admit("https://127.0.0.1:8443", "127.0.0.1:8443", target).ok());
  EXPECT_EQ(tls.Admit("http://127.0.0.1:8443", "127.0.0.1:8443", target).code(),
            absl::StatusCode::kPermissionDenied);
}

}  // namespace
}  // namespace hs::cli
