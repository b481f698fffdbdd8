// hapticctl against a haptic-server that serves TLS, with and without
// client certificates (mutual TLS), with certificates made at test time.

#include <gtest/gtest.h>

#include <sstream>

#include "client/exit_codes.h"
#include "client/health_command.h"
#include "server/haptic_server.h"
#include "tests/common/test_certificates.h"

namespace hs::cli {
namespace {

class TlsServer {
 public:
  explicit TlsServer(const std::string& client_ca) {
    const TestCertificates& c = MakeTestCertificates();
    ServerOptions options;
    options.listen = "127.0.0.1:0";
    options.tls = {c.server_cert, c.server_key, client_ca};
    absl::StatusOr<std::unique_ptr<HapticServer>> server = HapticServer::Start(options, metrics_);
    EXPECT_TRUE(server.ok()) << server.status();
    server_ = *std::move(server);
  }
  ~TlsServer() { server_->Shutdown(0.5); }
  std::string address() const { return "127.0.0.1:" + std::to_string(server_->port()); }

 private:
  Metrics metrics_;
  std::unique_ptr<HapticServer> server_;
};

// What `hapticctl health` exits with against `server` given `tls`.
int Health(const TlsServer& server, ConnectionOptions tls, std::string* err_text = nullptr) {
  HealthArgs args;
  args.server = std::move(tls);
  args.server.address = server.address();
  args.server.timeout_s = 5;
  std::ostringstream out, err;
  const int code = RunHealth(args, out, err);
  if (err_text != nullptr) *err_text = err.str();
  return code;
}

ConnectionOptions Tls(const std::filesystem::path& ca, const std::filesystem::path& cert = {},
                      const std::filesystem::path& key = {}) {
  ConnectionOptions o;
  o.tls_ca_file = ca;
  o.tls_cert_file = cert;
  o.tls_key_file = key;
  return o;
}

// A TLS server answers a client that trusts its CA, and no client that
// speaks plain TCP or trusts another CA.
TEST(TlsTest, ServerCertificateIsVerified) {
  const TestCertificates& c = MakeTestCertificates();
  TlsServer server("");
  std::string err;
  EXPECT_EQ(Health(server, Tls(c.ca), &err), kExitOk) << err;
  EXPECT_EQ(Health(server, ConnectionOptions{}), kExitUnavailable);
  const std::filesystem::path other_ca = c.ca.parent_path() / "other-ca.pem";
  EXPECT_EQ(Health(server, Tls(other_ca)), kExitUnavailable);
  // The certificate names 127.0.0.1, not this name.
  ConnectionOptions wrong_name = Tls(c.ca);
  wrong_name.tls_server_name = "elsewhere.example";
  EXPECT_EQ(Health(server, wrong_name), kExitUnavailable);
}

// With a client CA, only clients presenting a certificate that CA signed
// get an answer.
TEST(TlsTest, MutualTlsRequiresATrustedClientCertificate) {
  const TestCertificates& c = MakeTestCertificates();
  TlsServer server(c.ca);
  std::string err;
  EXPECT_EQ(Health(server, Tls(c.ca, c.client_cert, c.client_key), &err), kExitOk) << err;
  EXPECT_EQ(Health(server, Tls(c.ca)), kExitUnavailable);
  EXPECT_EQ(Health(server, Tls(c.ca, c.stranger_cert, c.stranger_key)), kExitUnavailable);
}

// Client-side mistakes are reported before any connection, naming the flag.
TEST(TlsTest, ClientOptionsAreChecked) {
  const TestCertificates& c = MakeTestCertificates();
  TlsServer server("");
  std::string err;
  EXPECT_EQ(Health(server, Tls("", c.client_cert, c.client_key), &err), kExitFailure);
  EXPECT_NE(err.find("need --tls-ca"), std::string::npos) << err;
  EXPECT_EQ(Health(server, Tls(c.ca, c.client_cert), &err), kExitFailure);
  EXPECT_NE(err.find("go together"), std::string::npos) << err;
}

}  // namespace
}  // namespace hs::cli
