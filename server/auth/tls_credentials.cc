#include "server/auth/tls_credentials.h"

#include <grpcpp/security/server_credentials.h>
#include <openssl/pem.h>
#include <openssl/x509.h>

#include <fstream>
#include <sstream>

#include "absl/strings/str_cat.h"

namespace hs {
namespace {

absl::StatusOr<std::string> ReadPem(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return absl::InvalidArgumentError(absl::StrCat("cannot read ", path));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// OpenSSL parses the PEM here, before gRPC does, so that a wrong file gets
// a message naming it instead of a failed handshake later.
struct Bio {
  explicit Bio(const std::string& pem)
      : bio(BIO_new_mem_buf(pem.data(), static_cast<int>(pem.size()))) {}
  ~Bio() { BIO_free(bio); }
  BIO* bio;
};

absl::Status CheckCertificate(const std::string& pem, const std::string& path) {
  Bio in(pem);
  X509* cert = PEM_read_bio_X509(in.bio, nullptr, nullptr, nullptr);
  if (cert == nullptr) {
    return absl::InvalidArgumentError(absl::StrCat(path, " holds no PEM certificate"));
  }
  X509_free(cert);
  return absl::OkStatus();
}

absl::Status CheckKeyMatches(const std::string& cert_pem, const ServerTlsFiles& files,
                             const std::string& key_pem) {
  Bio key_in(key_pem);
  EVP_PKEY* key = PEM_read_bio_PrivateKey(key_in.bio, nullptr, nullptr, nullptr);
  if (key == nullptr) {
    return absl::InvalidArgumentError(
        absl::StrCat(files.key_file, " holds no unencrypted PEM private key"));
  }
  Bio cert_in(cert_pem);
  X509* cert = PEM_read_bio_X509(cert_in.bio, nullptr, nullptr, nullptr);
  const bool matches = cert != nullptr && X509_check_private_key(cert, key) == 1;
  X509_free(cert);
  EVP_PKEY_free(key);
  if (!matches) {
    return absl::InvalidArgumentError(
        absl::StrCat(files.key_file, " is not the private key of ", files.cert_file));
  }
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<std::shared_ptr<grpc::ServerCredentials>> MakeServerCredentials(
    const ServerTlsFiles& files) {
  if (!files.enabled()) {
    if (!files.client_ca_file.empty()) {
      return absl::InvalidArgumentError(
          "a client CA needs a server certificate and key (--tls-cert, --tls-key)");
    }
    return grpc::InsecureServerCredentials();
  }
  if (files.cert_file.empty() || files.key_file.empty()) {
    return absl::InvalidArgumentError("TLS needs both a certificate and its key");
  }
  absl::StatusOr<std::string> cert = ReadPem(files.cert_file);
  if (!cert.ok()) return cert.status();
  if (absl::Status s = CheckCertificate(*cert, files.cert_file); !s.ok()) return s;
  absl::StatusOr<std::string> key = ReadPem(files.key_file);
  if (!key.ok()) return key.status();
  if (absl::Status s = CheckKeyMatches(*cert, files, *key); !s.ok()) return s;

  grpc::SslServerCredentialsOptions options;
  options.pem_key_cert_pairs.push_back({*key, *cert});
  if (!files.client_ca_file.empty()) {
    absl::StatusOr<std::string> ca = ReadPem(files.client_ca_file);
    if (!ca.ok()) return ca.status();
    if (absl::Status s = CheckCertificate(*ca, files.client_ca_file); !s.ok()) return s;
    options.pem_root_certs = *ca;
    options.client_certificate_request = GRPC_SSL_REQUEST_AND_REQUIRE_CLIENT_CERTIFICATE_AND_VERIFY;
  }
  return grpc::SslServerCredentials(options);
}

}  // namespace hs
