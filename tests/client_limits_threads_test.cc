// The client limits (issue 20) as scallopd's request threads share them: several threads at
// once admit and release calls and take from the token buckets, and every count comes out as
// the documented rules say. Labelled "threads", so ThreadSanitizer watches their locking
// (scripts/test-tsan.sh); built from the two limiters' sources alone (tests/CMakeLists.txt), so
// that its ThreadSanitizer build does not compile the rest of scallopd. Seeds printed.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "scallop/random/rng.h"
#include "server/admission_budget.h"
#include "server/rate_limiter.h"

namespace scallop::server {
namespace {

constexpr int kThreads = 4;

// Each thread owns 6 clients and admits or releases their calls at random: 6 clients of up to
// 4 calls each ask for more than the 16 in flight allowed, so each thread alone saturates the
// budget. After every admission the totals stay within the limits, and the thread's own
// clients within their share (a client with nothing in flight may start one call of any cost);
// saturation signals alternate; when all is released the budget is empty and free again.
TEST(ClientLimitsThreadsTest, AdmissionCountsHoldWhileThreadsAdmitAndRelease) {
  const AdmissionLimits limits{.max_calls = 16, .max_cost = 200, .client_share = 0.25};
  const int client_calls = 4;      // 16 x 0.25
  const int64_t client_cost = 50;  // 200 x 0.25
  AdmissionBudget budget(limits);
  bool last_signal = false;  // written under the budget's lock, where the callback runs
  int signals = 0;
  budget.OnSaturationChange([&](bool saturated) {
    EXPECT_NE(saturated, last_signal);
    last_signal = saturated;
    ++signals;
  });
  const uint64_t seed = 2027;
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      Rng rng(HashWords({seed, static_cast<uint64_t>(t)}));
      struct Client {
        std::string name;
        std::vector<int64_t> held;  // the costs of its calls in flight
        int64_t cost = 0;
      };
      std::vector<Client> clients;
      for (int c = 0; c < 6; ++c) clients.push_back({std::to_string(100 * t + c), {}, 0});
      for (int step = 0; step < 3000; ++step) {
        Client& client = clients[rng.Below(clients.size())];
        if (client.held.empty() || rng.Uniform() < 0.7) {
          const auto cost = static_cast<int64_t>(1 + rng.Below(60));
          const grpc::Status status = budget.TryAdmit(client.name, cost);
          if (!status.ok()) {
            EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
            continue;
          }
          client.held.push_back(cost);
          client.cost += cost;
          EXPECT_LE(budget.in_flight(), limits.max_calls) << "seed " << seed;
          EXPECT_LE(budget.cost_in_flight(), limits.max_cost) << "seed " << seed;
          if (client.held.size() > 1) {
            EXPECT_LE(client.held.size(), static_cast<size_t>(client_calls)) << "seed " << seed;
            EXPECT_LE(client.cost, client_cost) << "seed " << seed;
          }
        } else {
          const size_t k = rng.Below(client.held.size());
          budget.Release(client.name, client.held[k]);
          client.cost -= client.held[k];
          client.held[k] = client.held.back();
          client.held.pop_back();
        }
      }
      for (Client& client : clients) {
        for (int64_t cost : client.held) budget.Release(client.name, cost);
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  EXPECT_EQ(budget.in_flight(), 0);
  EXPECT_EQ(budget.cost_in_flight(), 0);
  EXPECT_FALSE(budget.saturated());
  EXPECT_GE(signals, 2) << "seed " << seed;  // saturated at least once, and free again
  EXPECT_EQ(signals % 2, 0) << "seed " << seed;
}

// At a fixed time no bucket refills, so however the threads interleave, each client gets exactly
// its burst: 6,000 clients (more than RateLimiter::kSweepAt, so the table is swept meanwhile)
// asked 8 times each by every thread, in an order of its own.
TEST(ClientLimitsThreadsTest, EachBucketGivesItsBurstOnceWhateverTheThreads) {
  const int burst = 5, clients = 6000, asks = 8;
  RateLimiter limiter(/*calls_per_second=*/1, burst);
  const auto now = RateLimiter::Clock::time_point{} + std::chrono::hours(1);
  const uint64_t seed = 2028;
  std::vector<std::string> names;
  for (int c = 0; c < clients; ++c) names.push_back(std::to_string(c));
  std::vector<std::vector<int>> allowed(kThreads, std::vector<int>(clients, 0));
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      Rng rng(HashWords({seed, static_cast<uint64_t>(t)}));
      std::vector<int> order;
      for (int c = 0; c < clients; ++c) order.insert(order.end(), asks, c);
      for (size_t k = order.size(); k > 1; --k) std::swap(order[k - 1], order[rng.Below(k)]);
      for (const int c : order) {
        const std::optional<double> wait = limiter.TryTake(names[static_cast<size_t>(c)], now);
        if (!wait) {
          ++allowed[static_cast<size_t>(t)][static_cast<size_t>(c)];
        } else {
          EXPECT_GT(*wait, 0.0);
        }
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  int wrong = 0;
  for (int c = 0; c < clients; ++c) {
    int total = 0;
    for (const std::vector<int>& by_thread : allowed) total += by_thread[static_cast<size_t>(c)];
    wrong += total != burst;
  }
  EXPECT_EQ(wrong, 0) << "clients not given exactly their burst, seed " << seed;
  EXPECT_EQ(limiter.clients(), static_cast<size_t>(clients));
}

}  // namespace
}  // namespace scallop::server
