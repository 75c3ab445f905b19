// Running make_test_certificates.sh into a mkdtemp folder, and reading its files.
#include "tests/e2e/test_certificates.h"

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

namespace scallop::testing {

std::string TestCertificates::Read(const std::string& name) const {
  std::ifstream file(Path(name));
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

client::ConnectionOptions TestCertificates::Connection(const std::string& ca,
                                                       const std::string& client,
                                                       const std::string& token) const {
  client::ConnectionOptions options;
  options.tls = true;
  options.tls_ca_pem = Read(ca);
  options.token = token;
  if (!client.empty()) {
    options.tls_cert_pem = Read(client + ".crt");
    options.tls_key_pem = Read(client + ".key");
  }
  return options;
}

std::optional<TestCertificates> MakeTestCertificates() {
  char dir_template[] = "/tmp/scallop-certs-XXXXXX";
  if (mkdtemp(dir_template) == nullptr) return std::nullopt;
  const std::string command =
      std::string("bash '") + SCALLOP_MAKE_TEST_CERTIFICATES + "' '" + dir_template + "'";
  if (std::system(command.c_str()) != 0) {
    std::cerr << "failed: " << command << '\n';
    return std::nullopt;
  }
  return TestCertificates{.dir = dir_template};
}

}  // namespace scallop::testing
