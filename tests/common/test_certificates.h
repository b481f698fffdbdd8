#pragma once
// Certificates made at test time with the openssl command: a CA, a server
// certificate for 127.0.0.1 and localhost, and client certificates, one
// signed by the CA and one by a CA the server does not trust.

#include <filesystem>
#include <string>

namespace hs {

struct TestCertificates {
  std::filesystem::path ca;            ///< The CA's certificate.
  std::filesystem::path server_cert;   ///< Signed by `ca`; 127.0.0.1, localhost.
  std::filesystem::path server_key;
  std::filesystem::path client_cert;   ///< Signed by `ca`.
  std::filesystem::path client_key;
  std::filesystem::path stranger_cert; ///< Signed by another CA.
  std::filesystem::path stranger_key;
};

/// Makes the set once per process (in a scratch dir); aborts the test
/// binary when openssl fails.
const TestCertificates& MakeTestCertificates();

}  // namespace hs
