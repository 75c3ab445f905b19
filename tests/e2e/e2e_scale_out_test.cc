// End to end: three scallopd replicas behind a client-side round_robin
// channel answer exactly as a single server does (points, ids, pages whose
// tokens cross replicas, streams, verify, descriptions), because replicas are
// stateless and agree by construction. Each replica's /metrics shows it
// served calls, so the balancing really happened.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "scallop/random/rng.h"
#include "tests/e2e/metrics_scrape.h"
#include "tests/e2e/scallopd_process.h"
#include "tests/test_worlds.h"
#include "world_messages.h"

namespace scallop::testing {
namespace {

constexpr int kReplicas = 3;

class E2eScaleOutTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    single_ = ScallopdProcess::Start({"--world", "hills:11:0.5:a1"}).release();
    std::string targets;
    for (int r = 0; r < kReplicas; ++r) {
      replicas_[r] =
          ScallopdProcess::Start({"--world", "hills:11:0.5:a1", "--metrics-listen", "127.0.0.1:0"})
              .release();
      if (replicas_[r] == nullptr) return;
      const std::string line = replicas_[r]->ReadStdoutLine(std::chrono::seconds(10));
      metrics_[r] = line.substr(line.rfind(' ') + 1);
      targets += (r ? "," : "") + replicas_[r]->address();
    }
    grpc::ChannelArguments arguments;
    arguments.SetLoadBalancingPolicyName("round_robin");
    balanced_ = new client::ScallopClient(grpc::CreateCustomChannel(
        "ipv4:" + targets, grpc::InsecureChannelCredentials(), arguments));
  }
  static void TearDownTestSuite() {
    delete balanced_;
    delete single_;
    for (ScallopdProcess*& replica : replicas_) delete replica;
  }
  void SetUp() override {
    ASSERT_NE(single_, nullptr);
    for (ScallopdProcess* replica : replicas_) ASSERT_NE(replica, nullptr);
  }

  static inline ScallopdProcess* single_ = nullptr;
  static inline ScallopdProcess* replicas_[kReplicas] = {};
  static inline std::string metrics_[kReplicas];
  static inline client::ScallopClient* balanced_ = nullptr;
};

// Random rectangles of random worlds, named and inline, across region seams.
TEST_F(E2eScaleOutTest, EveryAnswerEqualsASingleServers) {
  client::ScallopClient single = single_->Client();
  Rng rng(2027);
  for (int trial = 0; trial < 24; ++trial) {
    v1::GetPointsRequest request;
    if (trial % 3 == 0) {
      request.set_world_name("hills");
    } else {
      const WorldAlgorithm algorithm = trial % 3 == 1 ? WorldAlgorithm::kA3 : WorldAlgorithm::kA2;
      *request.mutable_world() = WorldToMessage(
          ValidWorld({.seed = rng.NextBits(), .min_distance = 1, .algorithm = algorithm}));
    }
    const double x = (rng.Uniform() - 0.5) * 2000, y = (rng.Uniform() - 0.5) * 2000;
    *request.mutable_rect() =
        RectToMessage({x, y, x + 5 + rng.Uniform() * 60, y + 5 + rng.Uniform() * 60});
    request.set_page_size(97);  // many pages, so tokens travel between replicas
    PlanePoints expected, got;
    ASSERT_TRUE(single.GetAllPoints(request, expected).ok());
    const grpc::Status status = balanced_->GetAllPoints(request, got);
    ASSERT_TRUE(status.ok()) << client::DescribeStatus(status);
    ASSERT_GT(expected.ids.size(), 0u);
    EXPECT_EQ(got.ids, expected.ids) << "trial " << trial;
    EXPECT_EQ(got.positions, expected.positions) << "trial " << trial;

    v1::StreamPointsRequest stream;
    if (request.has_world()) {
      *stream.mutable_world() = request.world();
    } else {
      stream.set_world_name(request.world_name());
    }
    *stream.mutable_rect() = request.rect();
    PlanePoints streamed;
    ASSERT_TRUE(balanced_->StreamAllPoints(stream, streamed).ok());
    EXPECT_EQ(streamed.ids, expected.ids);
  }
}

TEST_F(E2eScaleOutTest, VerifyAndDescribeAgree) {
  client::ScallopClient single = single_->Client();
  for (int call = 0; call < 2 * kReplicas; ++call) {
    v1::VerifyRequest verify;
    verify.set_world_name("hills");
    *verify.mutable_rect() = RectToMessage({-20.0 + call, -20, 20, 20});
    v1::VerifyResponse expected, got;
    ASSERT_TRUE(single.Verify(verify, expected).ok());
    ASSERT_TRUE(balanced_->Verify(verify, got).ok());
    EXPECT_EQ(got.SerializeAsString(), expected.SerializeAsString());
    EXPECT_TRUE(got.passed());

    v1::DescribeWorldRequest describe;
    describe.set_world_name("hills");
    v1::DescribeWorldResponse expected_world, got_world;
    ASSERT_TRUE(single.DescribeWorld(describe, expected_world).ok());
    ASSERT_TRUE(balanced_->DescribeWorld(describe, got_world).ok());
    EXPECT_EQ(got_world.SerializeAsString(), expected_world.SerializeAsString());
  }
}

// The planted fault: a replica whose "hills" differs. The comparison above
// must notice it (a different answer, or a page token the odd replica
// refuses, since tokens are keyed by the world set).
TEST_F(E2eScaleOutTest, AMisconfiguredReplicaIsCaught) {
  auto odd = ScallopdProcess::Start({"--world", "hills:12:0.5:a1"});
  ASSERT_NE(odd, nullptr);
  grpc::ChannelArguments arguments;
  arguments.SetLoadBalancingPolicyName("round_robin");
  client::ScallopClient mixed(
      grpc::CreateCustomChannel("ipv4:" + replicas_[0]->address() + "," + odd->address(),
                                grpc::InsecureChannelCredentials(), arguments));
  client::ScallopClient single = single_->Client();
  v1::GetPointsRequest request;
  request.set_world_name("hills");
  *request.mutable_rect() = RectToMessage({0, 0, 20, 20});
  PlanePoints expected;
  ASSERT_TRUE(single.GetAllPoints(request, expected).ok());
  // round_robin sends to the replicas that are connected: on a busy machine
  // the odd one may connect late, so keep calling (bounded) until it answers.
  int differing = 0;
  for (int call = 0; call < 200 && differing == 0; ++call) {
    PlanePoints got;
    if (!mixed.GetAllPoints(request, got).ok() || got.ids != expected.ids ||
        got.positions != expected.positions) {
      ++differing;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_GT(differing, 0) << "200 calls over 4 s never reached the misconfigured replica";
}

// Runs last in this file (gtest keeps declaration order): by now every
// replica must have answered some of the calls above.
TEST_F(E2eScaleOutTest, EveryReplicaServedCalls) {
  for (int r = 0; r < kReplicas; ++r) {
    std::map<std::string, double> metrics = ScrapeMetrics(metrics_[r]);
    double calls = 0;
    for (const auto& [key, value] : metrics) {
      if (key.rfind("scallop_requests_total{", 0) == 0) calls += value;
    }
    EXPECT_GT(calls, 0) << "replica " << r << " at " << replicas_[r]->address();
  }
}

}  // namespace
}  // namespace scallop::testing
