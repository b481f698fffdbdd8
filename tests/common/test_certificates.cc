#include "tests/common/test_certificates.h"

#include <cstdlib>
#include <fstream>

#include "common/core/check.h"
#include "tests/common/scratch_dir.h"

namespace hs {
namespace {

void Run(const std::string& command) {
  HS_CHECK(std::system((command + " >/dev/null 2>&1").c_str()) == 0);
}

// An EC key and a certificate for `name` signed by `ca` (self-signed: a CA).
void MakeCertificate(const std::filesystem::path& dir, const std::string& name,
                     const std::string& ca, const std::string& alt_names) {
  const std::string base = (dir / name).string();
  const std::string new_key =
      " -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes -keyout " + base + ".key";
  if (ca.empty()) {
    Run("openssl req -x509 -days 2 -subj /CN=" + name + new_key + " -out " + base + ".pem");
    return;
  }
  const std::string ext = base + ".ext";
  std::ofstream(ext) << (alt_names.empty() ? "" : "subjectAltName=" + alt_names + "\n");
  const std::string ca_base = (dir / ca).string();
  Run("openssl req -subj /CN=" + name + new_key + " -out " + base + ".csr");
  Run("openssl x509 -req -days 2 -in " + base + ".csr -CA " + ca_base + ".pem -CAkey " + ca_base +
      ".key -CAcreateserial -extfile " + ext + " -out " + base + ".pem");
}

TestCertificates Make() {
  const std::filesystem::path dir = ScratchDir("certificates");
  MakeCertificate(dir, "ca", "", "");
  MakeCertificate(dir, "server", "ca", "IP:127.0.0.1,DNS:localhost");
  MakeCertificate(dir, "client", "ca", "DNS:client");
  MakeCertificate(dir, "other-ca", "", "");
  MakeCertificate(dir, "stranger", "other-ca", "DNS:stranger");
  return TestCertificates{
      .ca = dir / "ca.pem",
      .server_cert = dir / "server.pem",
      .server_key = dir / "server.key",
      .client_cert = dir / "client.pem",
      .client_key = dir / "client.key",
      .stranger_cert = dir / "stranger.pem",
      .stranger_key = dir / "stranger.key",
  };
}

}  // namespace

const TestCertificates& MakeTestCertificates() {
  static const TestCertificates certificates = Make();
  return certificates;
}

}  // namespace hs
