#include "server/auth/tls_credentials.h"

#include <gtest/gtest.h>

#include <fstream>

#include "tests/common/scratch_dir.h"
#include "tests/common/test_certificates.h"

namespace hs {
namespace {

void ExpectInvalid(const ServerTlsFiles& files, const std::string& message) {
  absl::StatusOr<std::shared_ptr<grpc::ServerCredentials>> credentials =
      MakeServerCredentials(files);
  ASSERT_FALSE(credentials.ok()) << message;
  EXPECT_EQ(credentials.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(credentials.status().message().find(message), std::string::npos)
      << credentials.status();
}

// No files: plain credentials; a certificate with its key (and a client
// CA): TLS credentials.
TEST(TlsCredentialsTest, MakesPlainOrTlsCredentials) {
  const TestCertificates& c = MakeTestCertificates();
  EXPECT_TRUE(MakeServerCredentials({}).ok());
  EXPECT_TRUE(MakeServerCredentials({c.server_cert, c.server_key, ""}).ok());
  EXPECT_TRUE(MakeServerCredentials({c.server_cert, c.server_key, c.ca}).ok());
}

// Each unusable combination is refused with a message naming the file.
TEST(TlsCredentialsTest, RefusesUnusableFiles) {
  const TestCertificates& c = MakeTestCertificates();
  const std::filesystem::path dir = ScratchDir("tls-bad");
  const std::string not_pem = (dir / "not.pem").string();
  std::ofstream(not_pem) << "hello\n";
  const std::string missing = (dir / "missing.pem").string();

  ExpectInvalid({c.server_cert, "", ""}, "both a certificate and its key");
  ExpectInvalid({"", c.server_key, ""}, "both a certificate and its key");
  ExpectInvalid({"", "", c.ca}, "a client CA needs");
  ExpectInvalid({missing, c.server_key, ""}, "cannot read " + missing);
  ExpectInvalid({not_pem, c.server_key, ""}, not_pem + " holds no PEM certificate");
  ExpectInvalid({c.server_cert, not_pem, ""}, not_pem + " holds no unencrypted PEM private key");
  ExpectInvalid({c.server_cert, c.client_key, ""},
                c.client_key.string() + " is not the private key of " + c.server_cert.string());
  ExpectInvalid({c.server_cert, c.server_key, not_pem}, not_pem + " holds no PEM certificate");
}

}  // namespace
}  // namespace hs
