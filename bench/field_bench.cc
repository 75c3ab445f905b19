// Radius fields, bounded: SampleField on an r_max / r_min = 8 noise field against uniform A3
// (Sample, constant d) and the variable-radius Bridson baseline (k = 30), all in one run so
// the figures read as ratios. Points per second; N about 1M in the named benchmarks, 10k for a
// smoke run. On the infinite plane: a cold query (fresh engine, one thread) of a square of
// the same field world against the uniform A3 world (d = 1) on a square of the same count,
// N about 250k.
//
//   build/bench/field_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <cmath>

#include "bench/square_sampling.h"
#include "scallop/field/radius_field.h"
#include "scallop/field/value_noise.h"
#include "scallop/plane/plane_engine.h"
#include "scallop/sampling/field_sampler.h"
#include "scallop/sampling/sampler.h"

namespace scallop {
namespace {

// Noise over [1, 8] at 90% of the slope bound, 3 octaves.
RadiusField BenchField() {
  RadiusFieldSpec spec;
  spec.kind = RadiusFieldKind::kNoise;
  spec.r_min = 1.0;
  spec.r_max = 8.0;
  spec.noise_seed = 2026;
  spec.octaves = 3;
  spec.gain = 0.5;
  spec.frequency = 0.9 * kMaxFieldSlope / (7.0 * FractalValueNoiseSlope(1.0, 3, 0.5));
  return *RadiusField::Create(spec);
}

// A square expected to hold about `points` points of the field (measured: ~0.047 points per
// unit area for this field).
FieldSamplerOptions FieldOptionsFor(int64_t points) {
  FieldSamplerOptions options;
  const double side = std::sqrt(static_cast<double>(points) / 0.047);
  options.domain = {0.0, 0.0, side, side};
  return options;
}

void Report(benchmark::State& state, int64_t produced) {
  state.counters["points"] = static_cast<double>(produced);
  state.counters["points_per_second"] = benchmark::Counter(
      static_cast<double>(produced), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_FieldSampler(benchmark::State& state) {
  const RadiusField field = BenchField();
  FieldSamplerOptions options = FieldOptionsFor(state.range(0));
  int64_t produced = 0;
  FieldSampleStats stats;
  for (auto _ : state) {
    stats = {};
    auto points = SampleField(options, field, &stats);
    produced = static_cast<int64_t>(points->size());
    benchmark::DoNotOptimize(points->data());
    ++options.seed;
  }
  Report(state, produced);
  state.counters["swept_share"] = static_cast<double>(stats.swept) / static_cast<double>(produced);
  state.counters["evaluations_per_point"] =
      static_cast<double>(stats.evaluations) / static_cast<double>(produced);
  state.counters["spots_per_point"] =
      static_cast<double>(stats.curve_spots) / static_cast<double>(produced);
  state.counters["leaves_per_point"] =
      static_cast<double>(stats.leaves) / static_cast<double>(produced);
  state.counters["cells_per_point"] =
      static_cast<double>(stats.cells_tested) / static_cast<double>(produced);
}

void BM_FieldBridson(benchmark::State& state) {
  const RadiusField field = BenchField();
  FieldSamplerOptions options = FieldOptionsFor(state.range(0));
  int64_t produced = 0;
  for (auto _ : state) {
    auto points = SampleFieldBridson(options, field, 30);
    produced = static_cast<int64_t>(points->size());
    benchmark::DoNotOptimize(points->data());
    ++options.seed;
  }
  Report(state, produced);
}

// The control: uniform A3 at d = 1 on a square of about the same point count.
void BM_UniformA3(benchmark::State& state) {
  Report(state, SampleSquares(state, Algorithm::kA3, 0.8));
}

// Cold plane queries, a fresh one-thread engine per iteration: every region the square needs is
// generated (regions around it too). `field` selects the noise field world, else uniform A3.
void PlaneCold(benchmark::State& state, bool field) {
  WorldSpec spec{.seed = 2026, .min_distance = 1.0};
  if (field) spec.radius_field = BenchField().spec();
  const World world = *World::Create(spec);
  // Points per unit area: the field's 0.047 (above), A3's 0.86 at d = 1.
  const double density = field ? 0.047 : 0.86;
  const double side = std::sqrt(static_cast<double>(state.range(0)) / density);
  int64_t produced = 0;
  for (auto _ : state) {
    PlaneEngine engine(PlaneEngineOptions{.threads = 1});
    StatusOr<PlanePoints> points = engine.Points(world, {0.0, 0.0, side, side});
    produced = static_cast<int64_t>(points->positions.size());
    benchmark::DoNotOptimize(points->positions.data());
  }
  Report(state, produced);
}

void BM_PlaneColdUniform(benchmark::State& state) { PlaneCold(state, false); }
void BM_PlaneColdField(benchmark::State& state) { PlaneCold(state, true); }

BENCHMARK(BM_PlaneColdUniform)
    ->Name("plane_cold_uniform_a3_smoke")
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PlaneColdField)
    ->Name("plane_cold_field_noise8_smoke")
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PlaneColdUniform)
    ->Name("plane_cold_uniform_a3_250k")
    ->Arg(250000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PlaneColdField)
    ->Name("plane_cold_field_noise8_250k")
    ->Arg(250000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_UniformA3)->Name("uniform_a3_smoke")->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FieldSampler)->Name("field_noise8_smoke")->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FieldBridson)->Name("field_bridson_smoke")->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_UniformA3)->Name("uniform_a3_1M")->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FieldSampler)->Name("field_noise8_1M")->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FieldBridson)->Name("field_bridson_1M")->Arg(1000000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace scallop

BENCHMARK_MAIN();
