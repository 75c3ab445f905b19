// Cold tile latency of the engine alone: the CPU time one thread spends on a
// 64 d tile of a world nothing was generated for, at random places, as
// percentiles. Uses only PlaneEngine::Points, so the same source builds
// against any generator version for a before/after comparison in one run
// (docs/performance.md, "Cold tiles"). With more than one engine thread (as
// scallopd's `--threads 2`) it gives wall time instead: the engine's own
// share of a cold call's latency, the baseline of the load benchmark's cold
// rows.
//
// Usage: cold_tile_latency [tiles=400] [tile side in d=64] [engine threads=1]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "scallop/plane/plane_engine.h"
#include "scallop/random/rng.h"

namespace {

// Thread CPU time: the shared machine's load disturbs it far less than wall time.
double ThreadSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double WallSeconds() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

int main(int argc, char** argv) {
  const int tiles = argc > 1 ? std::atoi(argv[1]) : 400;
  const double side = argc > 2 ? std::atof(argv[2]) : 64.0;
  const int threads = argc > 3 ? std::atoi(argv[3]) : 1;
  if (tiles < 10 || !(side > 0) || threads < 1 || threads > 64) {
    std::fprintf(stderr, "usage: cold_tile_latency [tiles >= 10] [side > 0] [threads 1..64]\n");
    return 2;
  }
  // One thread generates on the calling thread, whose CPU time is the work;
  // a pool's work is on its threads, so wall time is what the caller waits.
  const bool wall = threads > 1;
  auto now = [wall] { return wall ? WallSeconds() : ThreadSeconds(); };
  scallop::Rng rng(42);
  std::vector<double> milliseconds;
  double points = 0;
  for (int n = 0; n < tiles; ++n) {
    // A fresh engine and world per tile: every region starts cold.
    scallop::PlaneEngine engine(scallop::PlaneEngineOptions{.threads = threads});
    const scallop::World world = *scallop::World::Create({.seed = 500 + static_cast<uint64_t>(n)});
    const double x = rng.Uniform(-1e4, 1e4), y = rng.Uniform(-1e4, 1e4);
    const double start = now();
    auto result = engine.Points(world, {x, y, x + side, y + side});
    milliseconds.push_back(1e3 * (now() - start));
    if (!result.ok()) {
      std::fprintf(stderr, "%s\n", result.status().message().c_str());
      return 1;
    }
    points += static_cast<double>(result->positions.size());
  }
  std::sort(milliseconds.begin(), milliseconds.end());
  auto at = [&](double q) { return milliseconds[static_cast<size_t>(q * (tiles - 1))]; };
  std::printf("%d cold %g d tiles, %.0f points each%s: median %.2f ms, p90 %.2f ms, p99 %.2f ms\n",
              tiles, side, points / tiles,
              wall ? (", wall time on " + std::to_string(threads) + " engine threads").c_str() : "",
              at(0.5), at(0.9), at(0.99));
  return 0;
}
