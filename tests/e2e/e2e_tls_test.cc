// End to end: scallopd over TLS and mutual TLS, with certificates made at test
// time. Each refusal is checked beside an acceptance on the same server, so a
// test cannot pass because the server is merely down.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/e2e/scallopd_process.h"
#include "tests/e2e/test_certificates.h"

namespace scallop::testing {
namespace {

// A deadline only bounds a refused handshake; success never waits on it.
grpc::Status AskInfo(client::ScallopClient client) {
  v1::GetServerInfoResponse info;
  return client.GetServerInfo(info, {.timeout = std::chrono::seconds(10)});
}

class E2eTlsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    certificates_ = MakeTestCertificates();
    ASSERT_TRUE(certificates_.has_value());
  }
  void TearDown() override {
    if (certificates_) std::filesystem::remove_all(certificates_->dir);
  }
  std::optional<TestCertificates> certificates_;
};

TEST_F(E2eTlsTest, TlsServesClientsThatTrustItsCaAndRefusesOthers) {
  const TestCertificates& c = *certificates_;
  auto server = ScallopdProcess::Start(
      {"--tls-cert", c.Path("server.crt"), "--tls-key", c.Path("server.key")}, "127.0.0.1:0",
      c.Connection("ca.crt"));
  ASSERT_NE(server, nullptr);
  EXPECT_TRUE(AskInfo(server->Client()).ok());
  // Plaintext to a TLS port: the handshake never completes.
  EXPECT_EQ(AskInfo(server->Client(client::ConnectionOptions{})).error_code(),
            grpc::StatusCode::UNAVAILABLE);
  // A client that trusts another CA does not accept the server's certificate.
  EXPECT_EQ(AskInfo(server->Client(c.Connection("other-ca.crt"))).error_code(),
            grpc::StatusCode::UNAVAILABLE);
}

TEST_F(E2eTlsTest, MutualTlsNeedsAClientCertificateItsCaSigned) {
  const TestCertificates& c = *certificates_;
  auto server = ScallopdProcess::Start({"--tls-cert", c.Path("server.crt"), "--tls-key",
                                        c.Path("server.key"), "--tls-client-ca", c.Path("ca.crt")},
                                       "127.0.0.1:0", c.Connection("ca.crt", "client"));
  ASSERT_NE(server, nullptr);
  EXPECT_TRUE(AskInfo(server->Client()).ok());
  EXPECT_EQ(AskInfo(server->Client(c.Connection("ca.crt"))).error_code(),
            grpc::StatusCode::UNAVAILABLE)
      << "no client certificate";
  EXPECT_EQ(AskInfo(server->Client(c.Connection("ca.crt", "other-client"))).error_code(),
            grpc::StatusCode::UNAVAILABLE)
      << "a client certificate another CA signed";
}

TEST_F(E2eTlsTest, ConfigFileTurnsTlsOnAsTheFlagsDo) {
  const TestCertificates& c = *certificates_;
  const std::string config = c.Path("scallopd.yaml");
  {
    std::ofstream file(config);
    file << "tls_cert: " << c.Path("server.crt") << "\ntls_key: " << c.Path("server.key")
         << "\ntls_client_ca: " << c.Path("ca.crt") << '\n';
  }
  auto server =
      ScallopdProcess::Start({"--config", config}, "127.0.0.1:0", c.Connection("ca.crt", "client"));
  ASSERT_NE(server, nullptr);
  EXPECT_TRUE(AskInfo(server->Client()).ok());
  EXPECT_EQ(AskInfo(server->Client(c.Connection("ca.crt"))).error_code(),
            grpc::StatusCode::UNAVAILABLE);
}

}  // namespace
}  // namespace scallop::testing
