// The geometry kernel under A1's load: ScallopedRegion::SubtractDisk on the inputs A1 gives it
// (an annulus s = 1 .. r' = 2 cut by r'-disks nearest first; a neighbour's region cut by an
// s-disk), and a whole A1 run at about 100k points for the end-to-end figure.
//
//   build/bench/geometry_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "bench/square_sampling.h"
#include "scallop/geometry/scalloped_region.h"
#include "scallop/random/rng.h"
#include "scallop/sampling/sampler.h"

namespace scallop {
namespace {

constexpr int kCases = 1024;
constexpr int kDisksPerAnnulus = 6;

struct Disk {
  Vec2 centre;
  double radius;
};

Vec2 RandomAt(Rng& rng, double low, double high) {
  const double angle = rng.Uniform(-std::numbers::pi, std::numbers::pi);
  const double distance = rng.Uniform(low, high);
  return {distance * std::cos(angle), distance * std::sin(angle)};
}

// A new point's annulus 1..2 and six r' = 2 disks at distances 1..4, nearest first (as A1).
std::vector<std::vector<Disk>> AnnulusCases() {
  Rng rng(11);
  std::vector<std::vector<Disk>> cases(kCases);
  for (auto& disks : cases) {
    for (int k = 0; k < kDisksPerAnnulus; ++k) disks.push_back({RandomAt(rng, 1.0, 4.0), 2.0});
    std::sort(disks.begin(), disks.end(), [](const Disk& a, const Disk& b) {
      return SquaredLength(a.centre) < SquaredLength(b.centre);
    });
  }
  return cases;
}

// Every SubtractDisk of a new point's neighbourhood: Reset, then six cuts.
void BM_SubtractDisk_NewPointAnnulus(benchmark::State& state) {
  const auto cases = AnnulusCases();
  ScallopedRegion region;
  size_t n = 0;
  int64_t calls = 0;
  for (auto _ : state) {
    const auto& disks = cases[n++ % cases.size()];
    region.Reset({0.0, 0.0}, 1.0, 2.0);
    for (const Disk& disk : disks) region.SubtractDisk(disk.centre, disk.radius);
    calls += kDisksPerAnnulus;
    benchmark::DoNotOptimize(region.Area());
  }
  // Seconds per call (kInvert of a rate); shown in the table in seconds.
  state.counters["s_per_SubtractDisk"] = benchmark::Counter(
      static_cast<double>(calls), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// Neighbours' regions (annulus 1..2 minus three r'-disks) cut by an s = 1 disk at distance
// 1..3 (a new point near them). The region copy is timed too; BM_RegionCopy measures it alone.
struct NeighbourCase {
  ScallopedRegion region;
  Disk cut;
};

std::vector<NeighbourCase> NeighbourCases() {
  Rng rng(12);
  std::vector<NeighbourCase> cases;
  while (cases.size() < static_cast<size_t>(kCases)) {
    ScallopedRegion region = ScallopedRegion::Annulus({0.0, 0.0}, 1.0, 2.0);
    for (int k = 0; k < 3; ++k) region.SubtractDisk(RandomAt(rng, 1.0, 4.0), 2.0);
    if (region.empty()) continue;
    cases.push_back({region, {RandomAt(rng, 1.0, 3.0), 1.0}});
  }
  return cases;
}

void BM_SubtractDisk_Neighbour(benchmark::State& state) {
  const auto cases = NeighbourCases();
  ScallopedRegion region;
  size_t n = 0;
  for (auto _ : state) {
    const NeighbourCase& c = cases[n++ % cases.size()];
    region = c.region;
    region.SubtractDisk(c.cut.centre, c.cut.radius);
    benchmark::DoNotOptimize(region.Area());
  }
}

void BM_RegionCopy(benchmark::State& state) {
  const auto cases = NeighbourCases();
  ScallopedRegion region;
  size_t n = 0;
  for (auto _ : state) {
    region = cases[n++ % cases.size()].region;
    benchmark::DoNotOptimize(region.Area());
  }
}

// A whole A1 run in a square expected to hold about 100k points (d = 1, r' = 2d).
void BM_A1(benchmark::State& state) {
  const int64_t produced = SampleSquares(state, Algorithm::kA1, 0.7);
  state.counters["points"] = static_cast<double>(produced);
  state.counters["points_per_second"] = benchmark::Counter(
      static_cast<double>(produced), benchmark::Counter::kIsIterationInvariantRate);
}

BENCHMARK(BM_SubtractDisk_NewPointAnnulus);
BENCHMARK(BM_SubtractDisk_Neighbour);
BENCHMARK(BM_RegionCopy);
BENCHMARK(BM_A1)->Arg(100000)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();

}  // namespace
}  // namespace scallop

BENCHMARK_MAIN();
