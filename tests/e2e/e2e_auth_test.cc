// End to end: bearer tokens (--auth-tokens) on every Scallop call, unary and
// streaming: missing or wrong -> UNAUTHENTICATED, a world outside a token's
// list -> PERMISSION_DENIED, health open without one; --no-reflection; and
// tokens over mutual TLS. Each refusal sits beside an acceptance.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "follow_client.h"
#include "grpc/reflection/v1alpha/reflection.grpc.pb.h"
#include "tests/e2e/scallopd_process.h"
#include "tests/e2e/test_certificates.h"
#include "world_messages.h"

namespace scallop::testing {
namespace {

constexpr const char* kAnyWorld = "any-world-token-0123456789";
constexpr const char* kCoastOnly = "coast-only-token-0123456789";

client::ConnectionOptions WithToken(const std::string& token) {
  client::ConnectionOptions options;
  options.token = token;
  return options;
}

// A deadline only bounds a failure; success never waits on it.
const client::CallOptions kCall{.timeout = std::chrono::seconds(20)};

grpc::StatusCode InfoCode(client::ScallopClient client) {
  v1::GetServerInfoResponse info;
  return client.GetServerInfo(info, kCall).error_code();
}

grpc::StatusCode DescribeCode(client::ScallopClient client, const std::string& world_name) {
  v1::DescribeWorldRequest request;
  if (!world_name.empty()) request.set_world_name(world_name);
  v1::DescribeWorldResponse response;
  return client.DescribeWorld(request, response, kCall).error_code();
}

grpc::StatusCode StreamCode(client::ScallopClient client, const std::string& world_name) {
  v1::StreamPointsRequest request;
  request.set_world_name(world_name);
  *request.mutable_rect() = RectToMessage({0, 0, 5, 5});
  PlanePoints points;
  return client.StreamAllPoints(request, points, kCall).error_code();
}

grpc::StatusCode FollowCode(const client::ScallopClient& client, const std::string& world_name) {
  client::FollowSession session(client, kCall);
  v1::FollowRequest request;
  request.set_world_name(world_name);
  *request.mutable_viewport() = RectToMessage({0, 0, 2, 2});
  grpc::Status status = session.Update(request, [](const v1::FollowResponse&) {});
  if (status.ok()) status = session.Finish();
  return status.error_code();
}

// Names of the services reflection lists, or the failed call's code.
grpc::StatusCode ReflectionCode(const client::ScallopClient& client) {
  auto stub = grpc::reflection::v1alpha::ServerReflection::NewStub(client.channel());
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(20));
  auto stream = stub->ServerReflectionInfo(&context);
  grpc::reflection::v1alpha::ServerReflectionRequest request;
  request.set_list_services("");
  stream->Write(request);
  stream->WritesDone();
  grpc::reflection::v1alpha::ServerReflectionResponse response;
  while (stream->Read(&response)) {
  }
  return stream->Finish().error_code();
}

class E2eAuthTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char dir_template[] = "/tmp/scallop-auth-XXXXXX";
    ASSERT_NE(mkdtemp(dir_template), nullptr);
    dir_ = dir_template;
    tokens_ = dir_ + "/tokens";
    std::ofstream file(tokens_);
    file << "# operators\n" << kAnyWorld << "\n\n  # the coast team\n" << kCoastOnly << " coast\n";
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::vector<std::string> Arguments() const {
    return {"--auth-tokens", tokens_, "--world", "coast:7:1:a3", "--world", "dense:9:0.5:a1"};
  }

  std::string dir_;
  std::string tokens_;
};

TEST_F(E2eAuthTest, CallsNeedAKnownTokenAndHealthDoesNot) {
  auto server = ScallopdProcess::Start(Arguments());  // waits on health, without a token
  ASSERT_NE(server, nullptr);
  EXPECT_EQ(InfoCode(server->Client()), grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_EQ(InfoCode(server->Client(WithToken("not-a-token-0123456789"))),
            grpc::StatusCode::UNAUTHENTICATED);
  // A prefix of a valid token is not a valid token.
  EXPECT_EQ(InfoCode(server->Client(WithToken(std::string(kAnyWorld).substr(0, 20)))),
            grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_EQ(InfoCode(server->Client(WithToken(kAnyWorld))), grpc::StatusCode::OK);
  EXPECT_EQ(StreamCode(server->Client(), "dense"), grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_EQ(StreamCode(server->Client(WithToken(kAnyWorld)), "dense"), grpc::StatusCode::OK);
  EXPECT_EQ(FollowCode(server->Client(), "dense"), grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_EQ(FollowCode(server->Client(WithToken(kAnyWorld)), "dense"), grpc::StatusCode::OK);
  bool serving = false;
  EXPECT_TRUE(server->Client().CheckHealth(serving, kCall).ok());
  EXPECT_TRUE(serving);
  // The refusal is logged as a failed call, like any other.
  EXPECT_NE(server->WaitForLog("UNAUTHENTICATED", std::chrono::seconds(20)).find("UNAUTHENTICATED"),
            std::string::npos);
}

TEST_F(E2eAuthTest, ATokenLimitedToWorldsIsDeniedTheOthers) {
  auto server = ScallopdProcess::Start(Arguments());
  ASSERT_NE(server, nullptr);
  const client::ConnectionOptions coast = WithToken(kCoastOnly);
  EXPECT_EQ(DescribeCode(server->Client(coast), "coast"), grpc::StatusCode::OK);
  EXPECT_EQ(DescribeCode(server->Client(coast), "dense"), grpc::StatusCode::PERMISSION_DENIED);
  // No world named: the default world ("default"), not in the list.
  EXPECT_EQ(DescribeCode(server->Client(coast), ""), grpc::StatusCode::PERMISSION_DENIED);
  EXPECT_EQ(DescribeCode(server->Client(WithToken(kAnyWorld)), ""), grpc::StatusCode::OK);
  // An inline world names no world: denied to a limited token, allowed to an unlimited one.
  v1::DescribeWorldRequest inline_world;
  inline_world.mutable_world()->set_seed(7);
  inline_world.mutable_world()->set_min_distance(1);
  inline_world.mutable_world()->set_algorithm(v1::ALGORITHM_A3);
  v1::DescribeWorldResponse response;
  EXPECT_EQ(server->Client(coast).DescribeWorld(inline_world, response, kCall).error_code(),
            grpc::StatusCode::PERMISSION_DENIED);
  EXPECT_EQ(server->Client(WithToken(kAnyWorld))
                .DescribeWorld(inline_world, response, kCall)
                .error_code(),
            grpc::StatusCode::OK);
  EXPECT_EQ(StreamCode(server->Client(coast), "coast"), grpc::StatusCode::OK);
  EXPECT_EQ(StreamCode(server->Client(coast), "dense"), grpc::StatusCode::PERMISSION_DENIED);
  EXPECT_EQ(FollowCode(server->Client(coast), "coast"), grpc::StatusCode::OK);
  EXPECT_EQ(FollowCode(server->Client(coast), "dense"), grpc::StatusCode::PERMISSION_DENIED);
  // GetServerInfo concerns no world: any valid token may ask.
  EXPECT_EQ(InfoCode(server->Client(coast)), grpc::StatusCode::OK);
}

TEST_F(E2eAuthTest, NoReflectionTurnsReflectionOff) {
  auto with = ScallopdProcess::Start({});
  ASSERT_NE(with, nullptr);
  EXPECT_EQ(ReflectionCode(with->Client()), grpc::StatusCode::OK);
  auto without = ScallopdProcess::Start({"--no-reflection"});
  ASSERT_NE(without, nullptr);
  EXPECT_EQ(ReflectionCode(without->Client()), grpc::StatusCode::UNIMPLEMENTED);
}

TEST_F(E2eAuthTest, TokensWorkOverMutualTls) {
  std::optional<TestCertificates> certificates = MakeTestCertificates();
  ASSERT_TRUE(certificates.has_value());
  const TestCertificates& c = *certificates;
  std::vector<std::string> arguments = Arguments();
  arguments.insert(arguments.end(), {"--tls-cert", c.Path("server.crt"), "--tls-key",
                                     c.Path("server.key"), "--tls-client-ca", c.Path("ca.crt")});
  auto server = ScallopdProcess::Start(arguments, "127.0.0.1:0", c.Connection("ca.crt", "client"));
  ASSERT_NE(server, nullptr);
  EXPECT_EQ(InfoCode(server->Client(c.Connection("ca.crt", "client", kAnyWorld))),
            grpc::StatusCode::OK);
  EXPECT_EQ(InfoCode(server->Client()), grpc::StatusCode::UNAUTHENTICATED);
  std::filesystem::remove_all(c.dir);
}

}  // namespace
}  // namespace scallop::testing
