// End to end (issue 20): limits no one client can exhaust alone, through a
// real scallopd. Per-token rate limits with a retry delay in the status
// details; one client's share of the stream slots; admission by cost, with
// health NOT_SERVING while saturated and SERVING after; idle connections
// closed; calls per connection capped. Each refusal sits beside an acceptance.
#include <gtest/gtest.h>

#include <atomic>
#include <fstream>
#include <thread>

#include "follow_client.h"
#include "grpc/health/v1/health.grpc.pb.h"
#include "tests/e2e/scallopd_process.h"
#include "tests/test_worlds.h"
#include "world_messages.h"

namespace scallop::testing {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

constexpr const char* kTokenA = "client-a-token-0123456789";
constexpr const char* kTokenB = "client-b-token-0123456789";

// A deadline only bounds a failure; success never waits on it.
const client::CallOptions kCall{.timeout = seconds(30)};

std::string WriteTokens() {
  const std::string path = ::testing::TempDir() + "e2e_client_limits_tokens";
  std::ofstream(path) << kTokenA << '\n' << kTokenB << '\n';
  return path;
}

client::ConnectionOptions WithToken(const std::string& token) {
  client::ConnectionOptions options;
  options.token = token;
  return options;
}

grpc::Status Describe(client::ScallopClient& client) {
  v1::DescribeWorldRequest request;
  v1::DescribeWorldResponse response;
  return client.DescribeWorld(request, response, kCall);
}

grpc::Status SmallGetPoints(client::ScallopClient& client) {
  v1::GetPointsRequest request;
  *request.mutable_rect() = RectToMessage({0, 0, 10, 10});
  v1::GetPointsResponse response;
  return client.GetPoints(request, response, kCall);
}

grpc::health::v1::HealthCheckResponse::ServingStatus Health(const client::ScallopClient& client,
                                                            const std::string& service = "") {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + seconds(10));
  grpc::health::v1::HealthCheckRequest request;
  request.set_service(service);
  grpc::health::v1::HealthCheckResponse health;
  const grpc::Status status =
      grpc::health::v1::Health::NewStub(client.channel())->Check(&context, request, &health);
  return status.ok() ? health.status() : grpc::health::v1::HealthCheckResponse::UNKNOWN;
}

// Polls until `done` or the deadline; true when `done` came first.
template <typename Done>
bool WaitFor(Done done, std::chrono::seconds limit) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  while (!done()) {
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(milliseconds(20));
  }
  return true;
}

TEST(E2eClientLimitsTest, ARateLimitedTokenWaitsAsToldAndOthersGoOn) {
  auto server = ScallopdProcess::Start({"--auth-tokens", WriteTokens(), "--rate-limit-per-second",
                                        "0.5", "--rate-limit-burst", "2"});
  ASSERT_NE(server, nullptr);
  client::ScallopClient a = server->Client(WithToken(kTokenA));
  client::ScallopClient b = server->Client(WithToken(kTokenB));
  // A burst of 2, then one call every 2 s: the third call at once is refused.
  for (int k = 0; k < 2; ++k) {
    const grpc::Status status = Describe(a);
    EXPECT_TRUE(status.ok()) << client::DescribeStatus(status);
  }
  const grpc::Status limited = Describe(a);
  EXPECT_EQ(limited.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(limited.error_message().find("rate_limit_per_second"), std::string::npos)
      << limited.error_message();
  const double wait = client::RetryAfterSeconds(limited);
  EXPECT_GT(wait, 0.0);
  EXPECT_LE(wait, 2.0);
  // Another token has its own bucket, streams included.
  EXPECT_TRUE(Describe(b).ok());
  EXPECT_TRUE(SmallGetPoints(b).ok());
  // After the delay the server asked for, the first token is served again.
  std::this_thread::sleep_for(std::chrono::duration<double>(wait + 0.05));
  const grpc::Status again = Describe(a);
  EXPECT_TRUE(again.ok()) << client::DescribeStatus(again);
}

v1::FollowRequest FirstUpdate() {
  v1::FollowRequest update;
  *update.mutable_world() = WorldToMessage(ValidWorld({.seed = 41}));
  *update.mutable_viewport() = RectToMessage({0, 0, 20, 20});
  return update;
}

TEST(E2eClientLimitsTest, OneClientHoldsAtMostItsShareOfTheStreams) {
  // 4 stream slots, half for one client.
  auto server = ScallopdProcess::Start({"--auth-tokens", WriteTokens(), "--max-streams-in-flight",
                                        "4", "--max-client-share", "0.5"});
  ASSERT_NE(server, nullptr);
  std::vector<std::unique_ptr<client::FollowSession>> sessions;
  auto open = [&](const client::ScallopClient& client) {
    sessions.push_back(std::make_unique<client::FollowSession>(client, kCall));
    return sessions.back()->Update(FirstUpdate(), [](const v1::FollowResponse&) {});
  };
  const client::ScallopClient a = server->Client(WithToken(kTokenA));
  const client::ScallopClient b = server->Client(WithToken(kTokenB));
  for (int k = 0; k < 2; ++k) ASSERT_TRUE(open(a).ok()) << k;
  const grpc::Status third = open(a);
  EXPECT_EQ(third.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(third.error_message().find("max_client_share"), std::string::npos)
      << third.error_message();
  // The other client still gets the rest.
  for (int k = 0; k < 2; ++k) {
    const grpc::Status status = open(b);
    EXPECT_TRUE(status.ok()) << client::DescribeStatus(status);
  }
}

// Two threads keep asking for cold 1000 d squares (about 4,000 regions each)
// against a cost budget of 5,000 regions: only one fits at a time, so the
// other is refused by cost, the server turns NOT_SERVING, small calls still
// get in, and once the big ones stop the server is SERVING again.
TEST(E2eClientLimitsTest, CostlyCallsSaturateTheBudgetAndHealthSaysSo) {
  auto server = ScallopdProcess::Start({"--max-in-flight-cost", "5000", "--max-client-share", "1",
                                        "--threads", "1", "--log-level", "warn"});
  ASSERT_NE(server, nullptr);
  client::ScallopClient client = server->Client();
  ASSERT_EQ(Health(client), grpc::health::v1::HealthCheckResponse::SERVING);
  std::atomic<bool> stop{false};
  std::atomic<int> refused_by_cost{0}, seed{100};
  auto big_calls = [&] {
    client::ScallopClient own = server->Client();
    for (int k = 0; k < 50 && !stop; ++k) {
      v1::GetPointsRequest request;
      *request.mutable_world() = WorldToMessage(ValidWorld({.seed = uint64_t(++seed)}));
      *request.mutable_rect() = RectToMessage({0, 0, 1000, 1000});
      request.set_page_size(1);
      v1::GetPointsResponse response;
      const grpc::Status status = own.GetPoints(request, response, kCall);
      if (status.error_code() == grpc::StatusCode::RESOURCE_EXHAUSTED &&
          status.error_message().find("max_in_flight_cost") != std::string::npos) {
        ++refused_by_cost;
      }
    }
  };
  std::thread first(big_calls), second(big_calls);
  const bool saw_not_serving =
      WaitFor([&] { return Health(client) == grpc::health::v1::HealthCheckResponse::NOT_SERVING; },
              seconds(120));
  EXPECT_TRUE(saw_not_serving);
  // Busy, not dead: a liveness probe must not restart it.
  EXPECT_EQ(Health(client, "liveness"), grpc::health::v1::HealthCheckResponse::SERVING);
  // A call of one region fits beside the one big call in flight.
  const grpc::Status small = SmallGetPoints(client);
  EXPECT_TRUE(small.ok()) << client::DescribeStatus(small);
  stop = true;
  first.join();
  second.join();
  EXPECT_GT(refused_by_cost.load(), 0);
  EXPECT_TRUE(
      WaitFor([&] { return Health(client) == grpc::health::v1::HealthCheckResponse::SERVING; },
              seconds(30)));
  EXPECT_NE(server->Log().find("saturated: health NOT_SERVING"), std::string::npos);
}

// A channel of its own: gRPC otherwise shares one connection between the
// channels of a process that name the same address.
std::shared_ptr<grpc::Channel> OwnConnection(const std::string& address) {
  grpc::ChannelArguments arguments;
  arguments.SetInt(GRPC_ARG_USE_LOCAL_SUBCHANNEL_POOL, 1);
  return grpc::CreateCustomChannel(address, grpc::InsecureChannelCredentials(), arguments);
}

TEST(E2eClientLimitsTest, IdleConnectionsAreClosed) {
  auto server = ScallopdProcess::Start({"--max-connection-idle-seconds", "0.5"});
  ASSERT_NE(server, nullptr);
  client::ScallopClient client(OwnConnection(server->address()));
  ASSERT_TRUE(Describe(client).ok());
  ASSERT_EQ(client.channel()->GetState(false), GRPC_CHANNEL_READY);
  // The server's GOAWAY after 0.5 s without a call takes the channel to IDLE.
  EXPECT_TRUE(
      WaitFor([&] { return client.channel()->GetState(false) == GRPC_CHANNEL_IDLE; }, seconds(30)));
  // And a client just reconnects.
  EXPECT_TRUE(Describe(client).ok());
}

TEST(E2eClientLimitsTest, CallsBeyondTheConnectionsLimitWaitForAnotherConnection) {
  auto server =
      ScallopdProcess::Start({"--max-calls-per-connection", "2", "--max-client-share", "1"});
  ASSERT_NE(server, nullptr);
  const client::ScallopClient client(OwnConnection(server->address()));
  std::vector<std::unique_ptr<client::FollowSession>> sessions;
  for (int k = 0; k < 2; ++k) {
    sessions.push_back(std::make_unique<client::FollowSession>(client, kCall));
    ASSERT_TRUE(sessions.back()->Update(FirstUpdate(), [](const v1::FollowResponse&) {}).ok());
  }
  // A third call on that connection waits for a stream the server never
  // grants while both are open (HTTP/2 SETTINGS_MAX_CONCURRENT_STREAMS).
  client::ScallopClient same(client.channel());
  v1::DescribeWorldRequest request;
  v1::DescribeWorldResponse response;
  const grpc::Status waited =
      same.DescribeWorld(request, response, {.timeout = milliseconds(1500)});
  EXPECT_EQ(waited.error_code(), grpc::StatusCode::DEADLINE_EXCEEDED)
      << client::DescribeStatus(waited);
  // Another connection is served at once.
  client::ScallopClient other(OwnConnection(server->address()));
  EXPECT_TRUE(Describe(other).ok());
  // And the first connection is served again once a session ends.
  EXPECT_TRUE(sessions.back()->Finish().ok());
  sessions.pop_back();
  EXPECT_TRUE(Describe(same).ok());
}

}  // namespace
}  // namespace scallop::testing
