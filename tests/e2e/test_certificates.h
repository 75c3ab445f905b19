// TLS material made at test time (make_test_certificates.sh, with the openssl
// command) in a fresh temporary folder: no key is ever checked in or reused.
#pragma once

#include <optional>
#include <string>

#include "scallop_client.h"

namespace scallop::testing {

struct TestCertificates {
  std::string dir;  // holds ca, server, client, other-ca and other-client .crt/.key
  std::string Path(const std::string& name) const { return dir + "/" + name; }
  // The text of a file in `dir` ("ca.crt").
  std::string Read(const std::string& name) const;
  // TLS that trusts `ca` ("ca.crt"), with the client pair `client` ("client"
  // for client.crt and client.key) when not empty, and `token` when not empty.
  client::ConnectionOptions Connection(const std::string& ca, const std::string& client = {},
                                       const std::string& token = {}) const;
};

// Nullopt (with the reason on stderr) when the openssl command failed.
std::optional<TestCertificates> MakeTestCertificates();

}  // namespace scallop::testing
