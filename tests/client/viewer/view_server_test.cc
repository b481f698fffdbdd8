// The viewer bridge's web side at its edge: a WebSocket opens only for the
// page's own origin with the bridge's secret (403 otherwise), the scene's
// data needs the secret, everything carries the page's security headers,
// a page that opens gets the scene and can take a tool, and with a
// certificate all of it is served over TLS.

#include "client/viewer/view_server.h"

#include <gtest/gtest.h>

#include "absl/strings/match.h"
#include "nlohmann/json.hpp"
#include "tests/client/viewer/bridge_client.h"
#include "tests/common/scratch_dir.h"
#include "tests/common/test_certificates.h"
#include "tests/server/test_server.h"

namespace hs::cli {
namespace {

using testing::Get;
using testing::PageClient;

class ViewServerTest : public ::testing::Test {
 protected:
  void SetUp() override { server_.Create(hs::testing::SmallScene("view")); }

  std::unique_ptr<ViewServer> Start(const ViewServerOptions& options = {}) {
    absl::StatusOr<std::unique_ptr<ViewServer>> view = ViewServer::Start(link_, options);
    EXPECT_TRUE(view.ok()) << view.status();
    return view.ok() ? std::move(*view) : nullptr;
  }

  hs::testing::TestServer server_;
  SceneLink link_{server_.channel(), "view"};
};

// The next message of `type` on `page` (null once the socket ends).
nlohmann::json NextOfType(PageClient& page, const std::string& type) {
  for (std::string text = page.Read(); !text.empty(); text = page.Read()) {
    nlohmann::json message = nlohmann::json::parse(text);
    if (message["type"] == type) return message;
  }
  return nullptr;
}

// Another site's page (another origin, even with the secret), and the
// page's own origin without the secret or with a wrong one, get 403; the
// page's own origin with the secret gets the socket and the scene.
TEST_F(ViewServerTest, UpgradeNeedsTheOwnOriginAndTheToken) {
  const auto view = Start();
  ASSERT_NE(view, nullptr);
  const uint16_t port = view->port();
  const std::string own = "http://127.0.0.1:" + std::to_string(port);
  const std::string with_token = "/ws?token=" + view->token();
  std::string wrong = view->token();
  wrong[0] = wrong[0] == 'a' ? 'b' : 'a';
  EXPECT_EQ(PageClient(port, "http://evil.example", with_token).status(), 403);
  EXPECT_EQ(PageClient(port, "http://127.0.0.1:" + std::to_string(port + 1), with_token).status(),
            403);
  EXPECT_EQ(PageClient(port, "", with_token).status(), 403);
  EXPECT_EQ(PageClient(port, own, "/ws").status(), 403);
  EXPECT_EQ(PageClient(port, own, "/ws?token=" + wrong).status(), 403);
  PageClient page(port, own, with_token);
  ASSERT_EQ(page.status(), 101);
  const nlohmann::json hello = NextOfType(page, "hello");
  ASSERT_FALSE(hello.is_null());
  EXPECT_EQ(hello["scene"], "view");
}

// The refusal says why and how to get in, and never quotes the secret.
TEST_F(ViewServerTest, RefusalsExplainWithoutTheToken) {
  const auto view = Start();
  ASSERT_NE(view, nullptr);
  const testing::HttpReply reply = Get(view->port(), "/geometry?token=" + view->token() + "0");
  EXPECT_EQ(reply.status, 403);
  EXPECT_TRUE(absl::StrContains(reply.body, "wrong viewer token")) << reply.body;
  EXPECT_TRUE(absl::StrContains(reply.body, "?token=")) << reply.body;
  EXPECT_FALSE(absl::StrContains(reply.body, view->token())) << reply.body;
}

// The page and its scripts are public; the scene's geometry and frames
// need the secret. Every answer carries the policy that allows the bridge
// alone, no sniffing and no referrer.
TEST_F(ViewServerTest, DataNeedsTheTokenAndAnswersCarryThePolicy) {
  const auto view = Start();
  ASSERT_NE(view, nullptr);
  const uint16_t port = view->port();
  for (const char* target : {"/geometry", "/frame"}) {
    EXPECT_EQ(Get(port, target).status, 403) << target;
    EXPECT_NE(Get(port, std::string(target) + "?token=" + view->token()).status, 403) << target;
  }
  for (const char* target : {"/", "/viewer.js", "/geometry", "/nothing"}) {
    testing::HttpReply reply = Get(port, target);
    ASSERT_NE(reply.status, 0) << target;
    EXPECT_TRUE(absl::StrContains(reply.headers["content-security-policy"], "default-src 'self'"))
        << target;
    EXPECT_TRUE(
        absl::StrContains(reply.headers["content-security-policy"], "frame-ancestors 'none'"));
    EXPECT_EQ(reply.headers["x-content-type-options"], "nosniff");
    EXPECT_EQ(reply.headers["referrer-policy"], "no-referrer");
  }
  EXPECT_EQ(Get(port, "/").status, 200);
}

// The announced address is the page's, secret included; each start makes
// a new secret.
TEST_F(ViewServerTest, UrlCarriesAFreshToken) {
  const auto first = Start();
  const auto second = Start();
  ASSERT_NE(first, nullptr);
  ASSERT_NE(second, nullptr);
  EXPECT_EQ(first->url(),
            "http://127.0.0.1:" + std::to_string(first->port()) + "/?token=" + first->token());
  EXPECT_NE(first->token(), second->token());
}

// A page that took a tool hears "held" from the server's Interact stream.
TEST_F(ViewServerTest, AdmittedPageTakesATool) {
  const auto view = Start();
  ASSERT_NE(view, nullptr);
  PageClient page(view->port(), "http://127.0.0.1:" + std::to_string(view->port()),
                  "/ws?token=" + view->token());
  ASSERT_EQ(page.status(), 101);
  page.Write(R"({"type":"take","tool":"probe"})");
  const nlohmann::json drive = NextOfType(page, "drive");
  ASSERT_FALSE(drive.is_null());
  EXPECT_EQ(drive["tool"], "probe");
  EXPECT_EQ(drive["state"], "held") << drive;
}

// With a certificate and key the page, its data and its socket are served
// over TLS (checked against the test CA), the socket for the https origin.
TEST_F(ViewServerTest, ServesOverTls) {
  const TestCertificates& c = MakeTestCertificates();
  ViewServerOptions options;
  options.tls_cert_file = c.server_cert.string();
  options.tls_key_file = c.server_key.string();
  const auto view = Start(options);
  ASSERT_NE(view, nullptr);
  const uint16_t port = view->port();
  EXPECT_TRUE(view->url().starts_with("https://127.0.0.1:")) << view->url();
  testing::HttpReply page = Get(port, "/", c.ca);
  EXPECT_EQ(page.status, 200);
  EXPECT_TRUE(absl::StrContains(page.headers["content-security-policy"], "default-src 'self'"));
  const std::string own = "https://127.0.0.1:" + std::to_string(port);
  EXPECT_EQ(PageClient(port, own, "/ws?token=" + view->token(), c.ca).status(), 101);
  EXPECT_EQ(PageClient(port, "http://127.0.0.1:" + std::to_string(port),
                       "/ws?token=" + view->token(), c.ca)
                .status(),
            403);
  // A client that speaks plain HTTP to it gets no answer.
  EXPECT_EQ(Get(port, "/").status, 0);
}

// TLS files that are missing, hold no key, or do not match are refused at
// start with INVALID_ARGUMENT naming the file.
TEST_F(ViewServerTest, BadTlsFilesAreNamed) {
  const TestCertificates& c = MakeTestCertificates();
  const std::string missing = (ScratchDir("bad_tls") / "missing.pem").string();
  struct Case {
    std::string cert, key, named;
  };
  for (const Case& bad :
       {Case{missing, c.server_key, missing}, Case{c.server_cert, c.server_cert, c.server_cert},
        Case{c.server_cert, c.client_key, c.client_key},
        Case{c.server_cert, "", "--http-tls-key"}}) {
    ViewServerOptions options;
    options.tls_cert_file = bad.cert;
    options.tls_key_file = bad.key;
    const absl::StatusOr<std::unique_ptr<ViewServer>> view = ViewServer::Start(link_, options);
    ASSERT_FALSE(view.ok()) << bad.cert << " " << bad.key;
    EXPECT_EQ(view.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_TRUE(absl::StrContains(view.status().message(), bad.named)) << view.status();
  }
}

}  // namespace
}  // namespace hs::cli
