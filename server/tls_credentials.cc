// Reading and checking the TLS files with OpenSSL, then gRPC's SSL credentials.
#include "server/tls_credentials.h"

#include <grpcpp/security/server_credentials.h>
#include <openssl/pem.h>
#include <openssl/x509.h>

#include <fstream>
#include <sstream>

namespace scallop::server {
namespace {

StatusOr<std::string> ReadFile(const std::string& setting, const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return InvalidArgument(setting + ": cannot read '" + path + "'");
  std::ostringstream text;
  text << file.rdbuf();
  if (file.bad()) return InvalidArgument(setting + ": cannot read '" + path + "'");
  return text.str();
}

// Parses the first certificate of `pem`; null when there is none.
X509* ParseCertificate(const std::string& pem) {
  BIO* bio = BIO_new_mem_buf(pem.data(), static_cast<int>(pem.size()));
  X509* certificate = PEM_read_bio_X509(bio, nullptr, nullptr, nullptr);
  BIO_free(bio);
  return certificate;
}

EVP_PKEY* ParsePrivateKey(const std::string& pem) {
  BIO* bio = BIO_new_mem_buf(pem.data(), static_cast<int>(pem.size()));
  EVP_PKEY* key = PEM_read_bio_PrivateKey(bio, nullptr, nullptr, nullptr);
  BIO_free(bio);
  return key;
}

}  // namespace

StatusOr<std::shared_ptr<grpc::ServerCredentials>> MakeServerCredentials(
    const ServerConfig& config) {
  if (config.tls_cert.empty()) return grpc::InsecureServerCredentials();
  StatusOr<std::string> cert = ReadFile("tls_cert", config.tls_cert);
  if (!cert.ok()) return cert.status();
  StatusOr<std::string> key = ReadFile("tls_key", config.tls_key);
  if (!key.ok()) return key.status();
  X509* certificate = ParseCertificate(*cert);
  if (certificate == nullptr) {
    return InvalidArgument("tls_cert: '" + config.tls_cert + "' holds no PEM certificate");
  }
  EVP_PKEY* private_key = ParsePrivateKey(*key);
  const bool matches =
      private_key != nullptr && X509_check_private_key(certificate, private_key) == 1;
  X509_free(certificate);
  EVP_PKEY_free(private_key);
  if (private_key == nullptr) {
    return InvalidArgument("tls_key: '" + config.tls_key +
                           "' holds no unencrypted PEM private key");
  }
  if (!matches) {
    return InvalidArgument("tls_key: '" + config.tls_key + "' is not the key of tls_cert '" +
                           config.tls_cert + "'");
  }
  grpc::SslServerCredentialsOptions options(GRPC_SSL_DONT_REQUEST_CLIENT_CERTIFICATE);
  options.pem_key_cert_pairs.push_back({.private_key = *key, .cert_chain = *cert});
  if (!config.tls_client_ca.empty()) {
    StatusOr<std::string> client_ca = ReadFile("tls_client_ca", config.tls_client_ca);
    if (!client_ca.ok()) return client_ca.status();
    X509* ca = ParseCertificate(*client_ca);
    if (ca == nullptr) {
      return InvalidArgument("tls_client_ca: '" + config.tls_client_ca +
                             "' holds no PEM certificate");
    }
    X509_free(ca);
    options.pem_root_certs = *client_ca;
    options.client_certificate_request = GRPC_SSL_REQUEST_AND_REQUIRE_CLIENT_CERTIFICATE_AND_VERIFY;
  }
  return grpc::SslServerCredentials(options);
}

}  // namespace scallop::server
