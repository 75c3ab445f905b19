// The paper's Table 1, today: every sampler at about 1k to 1M points in a
// rectangle, as points per second. Each run also times our Bridson on the
// same area, so every figure can be read as a ratio from one run, and the
// peak heap bytes per point. `a1_paper` is the paper's A1 (new points only within r' = 2 d of
// the set), which A1 was until it became exact dart throwing: the same-run baseline for A1.
//
//   build/bench/samplers_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <cmath>

#include "bench/allocation_counter.h"
#include "scallop/random/rng.h"
#include "scallop/sampling/sampler.h"
#include "scallop/sampling/sampling_problem.h"
#include "scallop/sampling/scalloped_sampler.h"

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

// Sample's A1 but restricted to spots within r' of the set: the paper's A1.
StatusOr<std::vector<Vec2>> SamplePapersA1(const SamplerOptions& options) {
  SamplingProblem problem;
  problem.domain = options.domain;
  problem.min_distance = options.min_distance;
  problem.density = options.density;
  Rng rng(HashWords({options.seed, static_cast<uint64_t>(Algorithm::kA1)}));
  return SampleScalloped(problem, CandidateChoice::kByArea, rng, A1Bulk::kCells,
                         A1Reach::kNearPoints);
}

// `papers_a1` runs SamplePapersA1 instead of Sample (with `algorithm` kA1).
void BM_Sampler(benchmark::State& state, Algorithm algorithm, bool papers_a1 = false) {
  SamplerOptions options = OptionsFor(algorithm, state.range(0));
  int64_t produced = 0;
  long long peak_bytes = 0;
  for (auto _ : state) {
    const long long baseline = bench::HeapBytes();
    bench::ResetHeapPeak();
    auto points = papers_a1 ? SamplePapersA1(options) : Sample(options);
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

#define SCALLOP_SAMPLER_BENCH(name, max_points, ...) \
  BENCHMARK_CAPTURE(BM_Sampler, name, __VA_ARGS__)   \
      ->RangeMultiplier(10)                          \
      ->Range(1000, max_points)                      \
      ->Unit(benchmark::kMillisecond)                \
      ->MinTime(0.5)

SCALLOP_SAMPLER_BENCH(bridson_baseline, 1000000, Algorithm::kBridson);
SCALLOP_SAMPLER_BENCH(a3, 1000000, Algorithm::kA3);
SCALLOP_SAMPLER_BENCH(a2, 1000000, Algorithm::kA2);
SCALLOP_SAMPLER_BENCH(a1, 1000000, Algorithm::kA1);
SCALLOP_SAMPLER_BENCH(a1_paper, 1000000, Algorithm::kA1, true);
SCALLOP_SAMPLER_BENCH(dart, 100000, Algorithm::kDartThrowing);
SCALLOP_SAMPLER_BENCH(best_candidate, 10000, Algorithm::kBestCandidate);

}  // namespace
}  // namespace scallop

BENCHMARK_MAIN();
