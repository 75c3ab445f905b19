// The infinite plane's speed, each figure beside its baseline from the same
// run: cold generation of a 1000 d square against bounded A3 on the same
// area, warm queries (all regions cached), cold speed-up with 2 threads, and
// bytes of cache per point.
//
//   build/bench/plane_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include "scallop/plane/plane_engine.h"
#include "scallop/sampling/sampler.h"

namespace scallop {
namespace {

constexpr double kSide = 1000.0;  // in d: about 850k A3 points

World BenchWorld(uint64_t seed) {
  return *World::Create({.seed = seed, .algorithm = WorldAlgorithm::kA3});
}

void SetPointsPerSecond(benchmark::State& state, int64_t points) {
  state.counters["points"] = static_cast<double>(points);
  state.counters["points_per_second"] = benchmark::Counter(
      static_cast<double>(points), benchmark::Counter::kIsIterationInvariantRate);
}

// Baseline: bounded A3 on the same square, one thread.
void BM_BoundedA3(benchmark::State& state) {
  SamplerOptions options;
  options.domain.rect = {0, 0, kSide, kSide};
  int64_t points = 0;
  for (auto _ : state) {
    auto result = Sample(options);
    points = static_cast<int64_t>(result->size());
    ++options.seed;
  }
  SetPointsPerSecond(state, points);
}
BENCHMARK(BM_BoundedA3)->Unit(benchmark::kMillisecond)->UseRealTime();

// Cold: a fresh engine per iteration, so every region is generated.
void BM_PlaneCold(benchmark::State& state) {
  PlaneEngineOptions options;
  options.threads = static_cast<int>(state.range(0));
  options.cache_bytes = int64_t{4} << 30;
  int64_t points = 0;
  uint64_t seed = 0;
  for (auto _ : state) {
    PlaneEngine engine(options);
    auto result = engine.Points(BenchWorld(++seed), {0, 0, kSide, kSide});
    points = static_cast<int64_t>(result->positions.size());
    state.PauseTiming();
    const RegionCacheStats stats = engine.CacheStats();
    state.counters["cache_bytes_per_point"] =
        static_cast<double>(stats.bytes) / static_cast<double>(points);
    state.ResumeTiming();
  }
  SetPointsPerSecond(state, points);
}
BENCHMARK(BM_PlaneCold)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// A1 worlds cold, one thread, on a 192 d square (about 26k points). Density 2 is dart throwing
// in every region (generator version 4); density 1.99 runs the paper's A1 (new points only
// within r' of the set), which density 2 ran until version 4: the baseline of the same run.
void BM_PlaneColdA1(benchmark::State& state) {
  constexpr double kA1Side = 192.0;
  const double density = static_cast<double>(state.range(0)) / 100.0;
  int64_t points = 0;
  uint64_t seed = 0;
  for (auto _ : state) {
    PlaneEngine engine(PlaneEngineOptions{.cache_bytes = int64_t{1} << 30, .threads = 1});
    const World world =
        *World::Create({.seed = ++seed, .algorithm = WorldAlgorithm::kA1, .density = density});
    auto result = engine.Points(world, {0, 0, kA1Side, kA1Side});
    points = static_cast<int64_t>(result->positions.size());
  }
  SetPointsPerSecond(state, points);
}
BENCHMARK(BM_PlaneColdA1)->Arg(200)->Arg(199)->Unit(benchmark::kMillisecond)->UseRealTime();

// Warm: every region cached; the query filters and copies points out.
void BM_PlaneWarm(benchmark::State& state) {
  PlaneEngineOptions options;
  options.threads = 1;
  options.cache_bytes = int64_t{4} << 30;
  PlaneEngine engine(options);
  const World world = BenchWorld(1);
  const Rect rect{0, 0, kSide, kSide};
  (void)engine.Points(world, rect);
  int64_t points = 0;
  for (auto _ : state) {
    auto result = engine.Points(world, rect);
    points = static_cast<int64_t>(result->positions.size());
    benchmark::DoNotOptimize(result->positions.data());
  }
  SetPointsPerSecond(state, points);
}
BENCHMARK(BM_PlaneWarm)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace scallop

BENCHMARK_MAIN();
