// Cold tile latency of the engine alone: the CPU time one thread spends on a
// 64 d tile of a world nothing was generated for, at random places, as
// percentiles. Uses only PlaneEngine::Points, so the same source builds
// against any generator version for a before/after comparison in one run
// (docs/performance.md, "Cold tiles"). With more than one engine thread (as
// scallopd's `--threads 2`) it gives wall time instead: the engine's own
// share of a cold call's latency, the baseline of the load benchmark's cold
// rows.
//
// With a cache budget (MiB) it runs as scallopd does under the load
// benchmark's cold mode instead: one engine with that cache, one A3 world, the
// load generator's cold tiles (bench/load_tile_plan.h), after a warm-up that
// fills the cache, so every measured tile also pays for evictions. It then
// gives wall time, and the process's CPU time and page faults a tile.
//
// Usage: cold_tile_latency [tiles=400] [tile side in d=64] [engine threads=1] [cache MiB]
#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "bench/load_tile_plan.h"
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

// User and system CPU time of the whole process (every engine thread), its
// minor page faults and its threads' voluntary context switches (a thread
// sleeping until work or a region it needs is ready) so far.
struct ProcessUsage {
  double seconds = 0;
  double faults = 0;
  double sleeps = 0;
};
ProcessUsage ProcessUsageNow() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  auto seconds = [](const timeval& t) {
    return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec);
  };
  return {seconds(usage.ru_utime) + seconds(usage.ru_stime), static_cast<double>(usage.ru_minflt),
          static_cast<double>(usage.ru_nvcsw)};
}

// The q-th quantile of `values`, sorted.
double At(const std::vector<double>& values, double q) {
  return values[static_cast<size_t>(q * static_cast<double>(values.size() - 1))];
}

// The cold mode of the load benchmark, the engine alone: `tiles` measured
// tiles after enough unmeasured ones to fill a cache of `cache_mib` MiB.
int RunWithCache(int tiles, double side, int threads, double cache_mib) {
  scallop::PlaneEngine engine(scallop::PlaneEngineOptions{
      .cache_bytes = static_cast<int64_t>(cache_mib * 1024 * 1024), .threads = threads});
  // The load generator's world for a cold run of seed 42, and its tiles.
  const scallop::World world = *scallop::World::Create(
      {.seed = 42, .min_distance = 1, .algorithm = scallop::WorldAlgorithm::kA3});
  const scallop::load::TilePlan plan(
      {.mode = scallop::load::LoadMode::kCold, .tile_side = side, .run_seed = 42});
  int64_t k = 0;
  auto query = [&] { return engine.Points(world, plan.Tile(k++)); };
  // Warm-up: until the cache evicts, then as many tiles again, so that the
  // measured ones find the cache full and the allocator in its steady state.
  while (engine.CacheStats().evictions == 0 && k < scallop::load::kMaxColdTiles / 2) {
    if (!query().ok()) return 1;
  }
  for (const int64_t filled = k; k < 2 * filled;) {
    if (!query().ok()) return 1;
  }
  std::vector<double> wall_ms;
  ProcessUsage total;
  double points = 0;
  const int64_t misses_before = engine.CacheStats().misses;
  for (int n = 0; n < tiles; ++n) {
    const ProcessUsage usage = ProcessUsageNow();
    const double start = WallSeconds();
    auto result = query();
    wall_ms.push_back(1e3 * (WallSeconds() - start));
    const ProcessUsage after = ProcessUsageNow();
    total.seconds += after.seconds - usage.seconds;
    total.faults += after.faults - usage.faults;
    total.sleeps += after.sleeps - usage.sleeps;
    if (!result.ok()) {
      std::fprintf(stderr, "%s\n", result.status().message().c_str());
      return 1;
    }
    points += static_cast<double>(result->positions.size());
  }
  const double generated = static_cast<double>(engine.CacheStats().misses - misses_before);
  std::sort(wall_ms.begin(), wall_ms.end());
  std::printf(
      "%d cold %g d tiles, %.0f points each, wall time on %d engine threads with a full %g MiB "
      "cache (%.1f regions generated a tile, %.0f tiles of warm-up): median %.2f ms, p90 %.2f ms, "
      "p99 %.2f ms; CPU %.0f us, %.1f page faults and %.1f thread sleeps a tile\n",
      tiles, side, points / tiles, threads, cache_mib, generated / tiles,
      static_cast<double>(k - tiles), At(wall_ms, 0.5), At(wall_ms, 0.9), At(wall_ms, 0.99),
      1e6 * total.seconds / tiles, total.faults / tiles, total.sleeps / tiles);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const int tiles = argc > 1 ? std::atoi(argv[1]) : 400;
  const double side = argc > 2 ? std::atof(argv[2]) : 64.0;
  const int threads = argc > 3 ? std::atoi(argv[3]) : 1;
  const double cache_mib = argc > 4 ? std::atof(argv[4]) : 0;
  if (tiles < 10 || !(side > 0) || side > 512 || threads < 1 || threads > 64 || !(cache_mib >= 0) ||
      cache_mib > 65536) {
    std::fprintf(stderr,
                 "usage: cold_tile_latency [tiles >= 10] [side 0..512] [threads 1..64] "
                 "[cache MiB 0..65536]\n");
    return 2;
  }
  if (cache_mib > 0) return RunWithCache(tiles, side, threads, cache_mib);
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
  std::printf("%d cold %g d tiles, %.0f points each%s: median %.2f ms, p90 %.2f ms, p99 %.2f ms\n",
              tiles, side, points / tiles,
              wall ? (", wall time on " + std::to_string(threads) + " engine threads").c_str() : "",
              At(milliseconds, 0.5), At(milliseconds, 0.9), At(milliseconds, 0.99));
  return 0;
}
