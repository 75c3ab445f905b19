// A simulated player walking 10,000 d at constant speed with a 64 d x 64 d
// view, against a real scallopd process on a loopback port (started as the
// end-to-end tests start it), three ways in one run: Follow with prefetch
// (velocity sent), Follow without (velocity 0), and the baseline, naive
// re-querying of the whole view with GetPoints each step. Each walk is on a
// fresh world, so every region starts cold.
//
//   build/bench/follow_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <thread>
#include <vector>

#include "follow_client.h"
#include "scallop/plane/world.h"
#include "scallop_client.h"
#include "tests/e2e/scallopd_process.h"
#include "world_messages.h"

namespace scallop {
namespace {

constexpr double kWalkLength = 10000;                    // in d, unless FOLLOW_BENCH_WALK_D
constexpr double kView = 64;                             // view side, in d
constexpr double kStep = 4;                              // d moved per update
constexpr auto kPace = std::chrono::microseconds(2000);  // one update every 2 ms
constexpr double kSpeed = kStep / 0.002;                 // 2000 d/s

struct WalkResult {
  int64_t steps = 0, bytes = 0, messages = 0, points = 0;
  double seconds = 0;
  std::vector<double> latencies_ms;  // per step, send to last message

  double Percentile(double p) {
    std::sort(latencies_ms.begin(), latencies_ms.end());
    const auto k = static_cast<size_t>(p * static_cast<double>(latencies_ms.size() - 1) + 0.5);
    return latencies_ms[k];
  }
};

enum class Mode { kFollowPrefetch, kFollowNoPrefetch, kNaiveGetPoints };

Rect ViewAt(int step, double y) {
  const double x = step * kStep;
  return {x, y, x + kView, y + kView};
}

// One walk along +x at row `y`; updates paced every kPace (sent at once when
// behind), so prefetch has the time a real player's motion gives it.
WalkResult Walk(const std::string& address, Mode mode, const World& world, double y,
                double walk_length) {
  client::ScallopClient client = client::ScallopClient::Connect(address);
  std::optional<client::FollowSession> session;
  if (mode != Mode::kNaiveGetPoints) session.emplace(client);
  WalkResult result;
  const int steps = static_cast<int>(walk_length / kStep);
  const auto start = std::chrono::steady_clock::now();
  for (int step = 0; step < steps; ++step) {
    std::this_thread::sleep_until(start + step * kPace);
    const Rect view = ViewAt(step, y);
    const auto sent = std::chrono::steady_clock::now();
    if (mode == Mode::kNaiveGetPoints) {
      v1::GetPointsRequest request;
      *request.mutable_world() = WorldToMessage(world);
      *request.mutable_rect() = RectToMessage(view);
      v1::GetPointsResponse response;
      if (!client.GetPoints(request, response).ok()) std::abort();
      result.bytes += static_cast<int64_t>(response.ByteSizeLong());
      result.messages += 1;
      result.points += response.points().ids_size();
    } else {
      v1::FollowRequest request;
      if (step == 0) *request.mutable_world() = WorldToMessage(world);
      *request.mutable_viewport() = RectToMessage(view);
      if (mode == Mode::kFollowPrefetch) request.set_velocity_x(kSpeed);
      const grpc::Status status = session->Update(request, [&](const v1::FollowResponse& response) {
        result.bytes += static_cast<int64_t>(response.ByteSizeLong());
        result.messages += 1;
        result.points += response.chunk().points().ids_size();
      });
      if (!status.ok()) std::abort();
    }
    result.latencies_ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - sent).count());
    ++result.steps;
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (session && !session->Finish().ok()) std::abort();
  return result;
}

// kWalkLength for the figures; FOLLOW_BENCH_WALK_D=<d> for a shorter walk
// (CI's smoke run walks a few steps, to show the benchmark still runs).
double WalkLength() {
  const char* text = std::getenv("FOLLOW_BENCH_WALK_D");
  const double length = text != nullptr ? std::atof(text) : 0;
  return length >= kStep ? length : kWalkLength;
}

void BM_WalkFollowVsNaive(benchmark::State& state) {
  // Its defaults, but no request log line per step.
  const std::unique_ptr<testing::ScallopdProcess> server =
      testing::ScallopdProcess::Start({"--log-level", "error"});
  if (!server) {
    std::cerr << "follow_bench: scallopd did not start\n";
    std::exit(1);
  }
  uint64_t seed = 100;
  for (auto _ : state) {
    const std::pair<const char*, Mode> modes[] = {{"prefetch", Mode::kFollowPrefetch},
                                                  {"no_prefetch", Mode::kFollowNoPrefetch},
                                                  {"naive", Mode::kNaiveGetPoints}};
    double naive_bytes = 0, prefetch_bytes = 0;
    std::map<Mode, double> p99;
    for (const auto& [name, mode] : modes) {
      WalkResult walk =
          Walk(server->address(), mode, *World::Create({.seed = ++seed}), 0, WalkLength());
      const std::string prefix = name;
      state.counters[prefix + "_bytes_per_s"] = static_cast<double>(walk.bytes) / walk.seconds;
      state.counters[prefix + "_msgs_per_s"] = static_cast<double>(walk.messages) / walk.seconds;
      state.counters[prefix + "_bytes_per_step"] =
          static_cast<double>(walk.bytes) / static_cast<double>(walk.steps);
      state.counters[prefix + "_p50_ms"] = walk.Percentile(0.50);
      // One step in four uncovers a new column of regions: p90 shows their
      // generation when it is on the critical path, p99 adds the machine's noise.
      state.counters[prefix + "_p90_ms"] = walk.Percentile(0.90);
      p99[mode] = walk.Percentile(0.99);
      state.counters[prefix + "_p99_ms"] = p99[mode];
      if (mode == Mode::kNaiveGetPoints) naive_bytes = static_cast<double>(walk.bytes);
      if (mode == Mode::kFollowPrefetch) prefetch_bytes = static_cast<double>(walk.bytes);
    }
    // The ratios are the figures that count on a shared, noisy machine.
    state.counters["naive_over_follow_bytes"] = naive_bytes / prefetch_bytes;
    state.counters["no_prefetch_over_prefetch_p99"] =
        p99[Mode::kFollowNoPrefetch] / p99[Mode::kFollowPrefetch];
    state.counters["naive_over_prefetch_p99"] =
        p99[Mode::kNaiveGetPoints] / p99[Mode::kFollowPrefetch];
  }
}
BENCHMARK(BM_WalkFollowVsNaive)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
}  // namespace scallop

BENCHMARK_MAIN();
