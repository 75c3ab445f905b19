// The paper's Table 1, today: every sampler at about 1k to 1M points in a
// rectangle, as points per second. Each run also times our Bridson on the
// same area, so every figure can be read as a ratio from one run, and the
// peak heap bytes per point.
//
//   build/bench/samplers_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <cmath>

#include "bench/allocation_counter.h"
#include "scallop/sampling/sampler.h"

namespace scallop {
namespace {

// A square domain expected to hold about `points` maximal points at d = 1
// (a maximal set has roughly 0.7 to 0.9 points per unit area).
SamplerOptions OptionsFor(Algorithm algorithm, int64_t points) {
  SamplerOptions options;
  options.algorithm = algorithm;
  const double side = std::sqrt(static_cast<double>(points) / 0.8);
  options.domain.rect = {0, 0, side, side};
  options.min_distance = 1.0;
  options.dart_failure_limit = 1000;
  options.best_candidate_factor = 1;
  return options;
}

void BM_Sampler(benchmark::State& state, Algorithm algorithm) {
  SamplerOptions options = OptionsFor(algorithm, state.range(0));
  int64_t produced = 0;
  long long peak_bytes = 0;
  for (auto _ : state) {
    const long long baseline = bench::HeapBytes();
    bench::ResetHeapPeak();
    auto points = Sample(options);
    peak_bytes = bench::HeapPeakSince(baseline);
    produced = static_cast<int64_t>(points->size());
    benchmark::DoNotOptimize(points->data());
    ++options.seed;
  }
  state.counters["points"] = static_cast<double>(produced);
  // Peak heap while sampling, output included, per point produced.
  state.counters["peak_bytes_per_point"] =
      static_cast<double>(peak_bytes) / static_cast<double>(produced);
  state.counters["points_per_second"] = benchmark::Counter(
      static_cast<double>(produced), benchmark::Counter::kIsIterationInvariantRate);
}

#define SCALLOP_SAMPLER_BENCH(name, algorithm, max_points) \
  BENCHMARK_CAPTURE(BM_Sampler, name, algorithm)           \
      ->RangeMultiplier(10)                                \
      ->Range(1000, max_points)                            \
      ->Unit(benchmark::kMillisecond)                      \
      ->MinTime(0.5)

SCALLOP_SAMPLER_BENCH(bridson_baseline, Algorithm::kBridson, 1000000);
SCALLOP_SAMPLER_BENCH(a3, Algorithm::kA3, 1000000);
SCALLOP_SAMPLER_BENCH(a2, Algorithm::kA2, 1000000);
SCALLOP_SAMPLER_BENCH(a1, Algorithm::kA1, 1000000);
SCALLOP_SAMPLER_BENCH(dart, Algorithm::kDartThrowing, 100000);
SCALLOP_SAMPLER_BENCH(best_candidate, Algorithm::kBestCandidate, 10000);

}  // namespace
}  // namespace scallop

BENCHMARK_MAIN();
