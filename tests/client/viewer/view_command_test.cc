// `hapticctl view` at its command line: it announces the page's address
// with a fresh secret and never prints the secret elsewhere; it refuses,
// with usage status 2 and before anything listens, a non-loopback address
// without TLS (unless told --insecure-http), half a TLS pair, and TLS
// files that do not load; with TLS it announces https.

#include "client/viewer/view_command.h"

#include <gtest/gtest.h>

#include <regex>
#include <sstream>

#include "absl/strings/match.h"
#include "client/exit_codes.h"
#include "tests/common/test_certificates.h"
#include "tests/server/test_server.h"

namespace hs::cli {
namespace {

struct ViewRun {
  int code = -1;
  std::string out, err;
};

ViewRun View(ViewArgs args) {
  std::ostringstream out, err;
  ViewRun run;
  run.code = RunView(args, out, err);
  run.out = out.str();
  run.err = err.str();
  return run;
}

class ViewCommandTest : public ::testing::Test {
 protected:
  void SetUp() override { server_.Create(hs::testing::SmallScene("seen")); }

  ViewArgs Args(const std::string& http) {
    ViewArgs args;
    args.server.address = server_.address();
    args.scene = "seen";
    args.http = http;
    args.duration_s = 0.2;
    return args;
  }

  hs::testing::TestServer server_;
};

// On loopback it announces http://HOST:PORT/?token= and 64 hex digits, and
// the secret appears nowhere else in its output.
TEST_F(ViewCommandTest, AnnouncesTheAddressWithItsToken) {
  const ViewRun run = View(Args("127.0.0.1:0"));
  ASSERT_EQ(run.code, kExitOk) << run.err;
  std::smatch match;
  ASSERT_TRUE(std::regex_search(
      run.out, match,
      std::regex(R"(^viewer on http://127\.0\.0\.1:\d+/\?token=([0-9a-f]{64})\n$)")))
      << run.out;
  EXPECT_FALSE(absl::StrContains(run.err, match[1].str())) << run.err;
  const ViewRun again = View(Args("127.0.0.1:0"));
  EXPECT_FALSE(absl::StrContains(again.out, match[1].str())) << "the secret is new at each start";
}

// An address other machines reach is refused without TLS, with a message
// that names both ways out; nothing is announced.
TEST_F(ViewCommandTest, NonLoopbackNeedsTlsOrInsecureHttp) {
  for (const char* http : {"0.0.0.0:0", "[::]:0", "192.0.2.10:0"}) {
    const ViewRun run = View(Args(http));
    EXPECT_EQ(run.code, kExitUsage) << http;
    EXPECT_TRUE(absl::StrContains(run.err, "--http-tls-cert")) << run.err;
    EXPECT_TRUE(absl::StrContains(run.err, "--insecure-http")) << run.err;
    EXPECT_EQ(run.out, "");
  }
}

// Half a TLS pair, or files that do not load (the key file holding a
// certificate), are usage errors naming what is wrong.
TEST_F(ViewCommandTest, BadTlsFilesAreUsageErrors) {
  const TestCertificates& c = MakeTestCertificates();
  ViewArgs half = Args("127.0.0.1:0");
  half.http_tls_cert = c.server_cert.string();
  const ViewRun half_run = View(half);
  EXPECT_EQ(half_run.code, kExitUsage);
  EXPECT_TRUE(absl::StrContains(half_run.err, "--http-tls-key")) << half_run.err;
  ViewArgs wrong = half;
  wrong.http_tls_key = c.server_cert.string();
  const ViewRun wrong_run = View(wrong);
  EXPECT_EQ(wrong_run.code, kExitUsage);
  EXPECT_TRUE(absl::StrContains(wrong_run.err, c.server_cert.string())) << wrong_run.err;
  EXPECT_EQ(wrong_run.out, "");
}

// With a certificate and key the page's address is https.
TEST_F(ViewCommandTest, TlsAnnouncesHttps) {
  const TestCertificates& c = MakeTestCertificates();
  ViewArgs args = Args("127.0.0.1:0");
  args.http_tls_cert = c.server_cert.string();
  args.http_tls_key = c.server_key.string();
  const ViewRun run = View(args);
  ASSERT_EQ(run.code, kExitOk) << run.err;
  EXPECT_TRUE(run.out.starts_with("viewer on https://127.0.0.1:")) << run.out;
}

}  // namespace
}  // namespace hs::cli
