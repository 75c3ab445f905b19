// The benchmark loop shared by the bounded samplers' whole-run benchmarks: one
// Sample of a square sized to hold about state.range(0) points at d = 1, a
// new seed each iteration.
#pragma once

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>

#include "scallop/sampling/sampler.h"

namespace scallop {

// `points_per_d2` is the algorithm's density at d = 1 (0.7 for A1 at
// r' = 2d, 0.8 for A3), which sizes the square. Returns the last run's count.
inline int64_t SampleSquares(benchmark::State& state, Algorithm algorithm, double points_per_d2) {
  SamplerOptions options;
  options.algorithm = algorithm;
  const double side = std::sqrt(static_cast<double>(state.range(0)) / points_per_d2);
  options.domain.rect = {0.0, 0.0, side, side};
  options.min_distance = 1.0;
  int64_t produced = 0;
  for (auto _ : state) {
    auto points = Sample(options);
    produced = static_cast<int64_t>(points->size());
    benchmark::DoNotOptimize(points->data());
    ++options.seed;
  }
  return produced;
}

}  // namespace scallop
