// The limits no one client can exhaust alone (issue 20): the admission
// budget's three counts and its saturation signal, the per-client token
// buckets, the client key, and the retry delay a refusal carries. Each check
// is against numbers worked out by hand from the documented rules.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <vector>

#include "scallop_client.h"
#include "server/admission_budget.h"
#include "server/client_key.h"
#include "server/rate_limiter.h"
#include "server/retry_status.h"

namespace scallop::server {
namespace {

bool Contains(const grpc::Status& status, const std::string& text) {
  return status.error_message().find(text) != std::string::npos;
}

TEST(AdmissionBudgetTest, CountsCallsAndRefusesBeyondTheLimitNamingIt) {
  AdmissionBudget budget({.max_calls = 4, .max_cost = 1000, .client_share = 1});
  for (int k = 0; k < 4; ++k) EXPECT_TRUE(budget.TryAdmit("a", 1).ok()) << k;
  const grpc::Status refused = budget.TryAdmit("a", 1);
  EXPECT_EQ(refused.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_TRUE(Contains(refused, "max_in_flight")) << refused.error_message();
  budget.Release("a", 1);
  EXPECT_TRUE(budget.TryAdmit("a", 1).ok());
  EXPECT_EQ(budget.in_flight(), 4);
}

TEST(AdmissionBudgetTest, CostIsCountedAndClampedToTheBudget) {
  AdmissionBudget budget({.max_calls = 10, .max_cost = 100, .client_share = 1});
  EXPECT_TRUE(budget.TryAdmit("a", 60).ok());
  // 60 + 50 > 100: refused for its cost, naming the setting.
  const grpc::Status refused = budget.TryAdmit("b", 50);
  EXPECT_EQ(refused.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_TRUE(Contains(refused, "max_in_flight_cost")) << refused.error_message();
  EXPECT_TRUE(budget.TryAdmit("b", 40).ok());
  EXPECT_EQ(budget.cost_in_flight(), 100);
  budget.Release("a", 60);
  budget.Release("b", 40);
  // A call costlier than the whole budget counts as the whole budget: alone
  // it runs, and it holds everything while it does.
  EXPECT_TRUE(budget.TryAdmit("a", 1'000'000).ok());
  EXPECT_EQ(budget.cost_in_flight(), 100);
  EXPECT_FALSE(budget.TryAdmit("b", 1).ok());
  budget.Release("a", 1'000'000);
  EXPECT_EQ(budget.cost_in_flight(), 0);
  // Zero or negative costs count as 1.
  EXPECT_TRUE(budget.TryAdmit("a", 0).ok());
  EXPECT_EQ(budget.cost_in_flight(), 1);
}

TEST(AdmissionBudgetTest, OneClientGetsItsShareAndTheOthersTheRest) {
  // Share 1/2 of 8 calls and 100 regions: 4 calls or 50 regions a client.
  AdmissionBudget budget({.max_calls = 8, .max_cost = 100, .client_share = 0.5});
  for (int k = 0; k < 4; ++k) EXPECT_TRUE(budget.TryAdmit("greedy", 1).ok()) << k;
  const grpc::Status refused = budget.TryAdmit("greedy", 1);
  EXPECT_EQ(refused.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_TRUE(Contains(refused, "max_client_share 0.5")) << refused.error_message();
  // Others are not affected, and a share refusal is not saturation.
  EXPECT_FALSE(budget.saturated());
  for (int k = 0; k < 4; ++k) EXPECT_TRUE(budget.TryAdmit("other", 1).ok()) << k;
  // Cost share: after one ends, 3 calls hold 3 regions; 3 + 48 > 50.
  budget.Release("greedy", 1);
  EXPECT_FALSE(budget.TryAdmit("greedy", 48).ok());
  EXPECT_TRUE(budget.TryAdmit("greedy", 47).ok());
}

TEST(AdmissionBudgetTest, AClientWithNothingInFlightMayStartOneCostlyCall) {
  AdmissionBudget budget({.max_calls = 8, .max_cost = 100, .client_share = 0.25});
  // 80 regions is over the client's 25, but it has nothing in flight.
  EXPECT_TRUE(budget.TryAdmit("a", 80).ok());
  EXPECT_FALSE(budget.TryAdmit("a", 1).ok());
  EXPECT_TRUE(budget.TryAdmit("b", 20).ok());
}

TEST(AdmissionBudgetTest, SaturationStartsAtARefusalForRoomAndEndsWhenHalfIsFree) {
  AdmissionBudget budget({.max_calls = 4, .max_cost = 1000, .client_share = 1});
  std::vector<bool> changes;
  budget.OnSaturationChange([&](bool saturated) { changes.push_back(saturated); });
  for (int k = 0; k < 4; ++k) ASSERT_TRUE(budget.TryAdmit("a", 1).ok());
  EXPECT_FALSE(budget.saturated());  // full, but nobody was refused yet
  EXPECT_FALSE(budget.TryAdmit("a", 1).ok());
  EXPECT_TRUE(budget.saturated());
  budget.Release("a", 1);  // 3 of 4 in flight: still saturated
  EXPECT_TRUE(budget.saturated());
  budget.Release("a", 1);  // 2 of 4: half free
  EXPECT_FALSE(budget.saturated());
  EXPECT_EQ(changes, (std::vector<bool>{true, false}));
}

TEST(RateLimiterTest, BurstThenRateThenRefillPerClient) {
  RateLimiter limiter(/*calls_per_second=*/2, /*burst=*/3);
  const auto t0 = RateLimiter::Clock::time_point{} + std::chrono::hours(1);
  for (int k = 0; k < 3; ++k) EXPECT_FALSE(limiter.TryTake("a", t0).has_value()) << k;
  // Empty: the next call is half a second away at 2 a second.
  const std::optional<double> wait = limiter.TryTake("a", t0);
  ASSERT_TRUE(wait.has_value());
  EXPECT_DOUBLE_EQ(*wait, 0.5);
  // Another client has its own bucket.
  EXPECT_FALSE(limiter.TryTake("b", t0).has_value());
  // 0.5 s later one call is back, and only one.
  const auto t1 = t0 + std::chrono::milliseconds(500);
  EXPECT_FALSE(limiter.TryTake("a", t1).has_value());
  EXPECT_TRUE(limiter.TryTake("a", t1).has_value());
  // Long idle refills to the burst, no more.
  const auto t2 = t1 + std::chrono::hours(1);
  for (int k = 0; k < 3; ++k) EXPECT_FALSE(limiter.TryTake("a", t2).has_value()) << k;
  EXPECT_TRUE(limiter.TryTake("a", t2).has_value());
}

TEST(RateLimiterTest, OffWhenTheRateIsZero) {
  RateLimiter limiter(0, 1);
  for (int k = 0; k < 1000; ++k) ASSERT_FALSE(limiter.TryTake("a").has_value());
  EXPECT_EQ(limiter.clients(), 0u);
}

TEST(RateLimiterTest, TheTableForgetsClientsWhoseBucketsRefilled) {
  RateLimiter limiter(1000, 1);
  const auto t0 = RateLimiter::Clock::time_point{} + std::chrono::hours(1);
  for (size_t k = 0; k < RateLimiter::kSweepAt; ++k) limiter.TryTake(std::to_string(k), t0);
  EXPECT_EQ(limiter.clients(), RateLimiter::kSweepAt);
  // A second later every bucket is full again: the next new client sweeps them.
  limiter.TryTake("late", t0 + std::chrono::seconds(1));
  EXPECT_EQ(limiter.clients(), 1u);
}

TEST(ClientKeyTest, PeersLoseTheirPortSoOneHostIsOneClient) {
  EXPECT_EQ(PeerKey("ipv4:10.0.0.7:51234"), "peer:ipv4:10.0.0.7");
  EXPECT_EQ(PeerKey("ipv4:10.0.0.7:40000"), PeerKey("ipv4:10.0.0.7:51234"));
  EXPECT_EQ(PeerKey("ipv6:[::1]:50051"), "peer:ipv6:[::1]");
  EXPECT_EQ(PeerKey("unix:/tmp/socket"), "peer:unix:/tmp/socket");
  EXPECT_NE(PeerKey("ipv4:10.0.0.7:1"), PeerKey("ipv4:10.0.0.8:1"));
}

TEST(RetryStatusTest, TheDelayTravelsInTheDetailsAndTheMessage) {
  const grpc::Status status = ResourceExhaustedRetryAfter("server: slow down", 0.25);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(status.error_message(), "server: slow down; retry after 0.25 s");
  EXPECT_DOUBLE_EQ(client::RetryAfterSeconds(status), 0.25);
  // Rounded up to the millisecond, never down to zero.
  EXPECT_DOUBLE_EQ(client::RetryAfterSeconds(ResourceExhaustedRetryAfter("x", 1e-7)), 0.001);
  // A status without details has no delay.
  EXPECT_EQ(client::RetryAfterSeconds(grpc::Status(grpc::StatusCode::RESOURCE_EXHAUSTED, "x")), -1);
}

}  // namespace
}  // namespace scallop::server
