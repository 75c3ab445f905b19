// What a warm GetPoints costs scallopd before gRPC takes over: random 64 d
// tiles of a warm 256 d square (the load benchmark's warm mode), their cached
// regions' points copied into a Points message as AnswerGetPoints does it,
// beside a control from the same run.
//
//   build/bench/warm_answer_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <vector>

#include "encoded_points.h"
#include "scallop/plane/plane_engine.h"
#include "scallop/random/rng.h"

namespace scallop {
namespace {

constexpr double kTile = 64;        // d, as load_generator --tile
constexpr double kWarmSide = 256;   // d, as load_generator --warm-side
constexpr int kTilesPerPass = 256;  // distinct tiles, so the regions are not all in L1

struct WarmTiles {
  PlaneEngine engine{{.threads = 1}};
  World world = *World::Create({.seed = 1});
  std::vector<std::vector<RegionHandle>> regions;  // of each tile
  std::vector<Rect> rects;

  WarmTiles() {
    (void)engine.Points(world, {0, 0, kWarmSide, kWarmSide});
    Rng rng(5);
    for (int k = 0; k < kTilesPerPass; ++k) {
      const double x0 = rng.Uniform(0, kWarmSide - kTile), y0 = rng.Uniform(0, kWarmSide - kTile);
      rects.push_back({x0, y0, x0 + kTile, y0 + kTile});
      regions.push_back(*engine.CachedRegions(world, rects.back()));
    }
  }
};

void SetPointsPerSecond(benchmark::State& state, int64_t points) {
  state.counters["points_per_second"] =
      benchmark::Counter(static_cast<double>(points), benchmark::Counter::kIsRate);
  state.counters["ns_per_point"] = benchmark::Counter(
      static_cast<double>(points), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// The control: VisitPoints as it was before the branch-free filter (a
// branch a point of every region the tile cuts), the same appender.
template <typename Visit>
size_t VisitWithBranches(const std::vector<RegionHandle>& regions, const RegionLayout& layout,
                         const Rect& rect, Visit visit) {
  size_t count = 0;
  for (const RegionHandle& region : regions) {
    const uint64_t first_id = EncodePointId(region->key, 0, layout.point_id_index_bits());
    for (size_t k = 0; k < region->points.size(); ++k) {
      if (!rect.Contains(region->points[k])) continue;
      visit(region->points[k], first_id + k);
      ++count;
    }
  }
  return count;
}

// Each pass: every tile's points through `visit_points` into a packed Points message.
template <typename VisitPointsOf>
void TimeWarmAnswers(benchmark::State& state, VisitPointsOf visit_points) {
  WarmTiles tiles;
  const RegionLayout layout(tiles.world);
  int64_t points = 0;
  for (auto _ : state) {
    for (int k = 0; k < kTilesPerPass; ++k) {
      const std::vector<RegionHandle>& regions = tiles.regions[static_cast<size_t>(k)];
      size_t upper_bound = 0;
      for (const RegionHandle& region : regions) upper_bound += region->points.size();
      v1::Points message;
      WritePoints(message, PointEncoding::kPacked, tiles.world, upper_bound, [&](auto& appender) {
        points += static_cast<int64_t>(
            visit_points(regions, layout, tiles.rects[static_cast<size_t>(k)],
                         [&](const Vec2& p, uint64_t id) { appender.Append(p, id); }));
      });
      benchmark::DoNotOptimize(message.xs().data());
    }
  }
  SetPointsPerSecond(state, points);
}

void BM_WarmAnswerControl(benchmark::State& state) {
  TimeWarmAnswers(state, [](const auto& regions, const auto& layout, const Rect& rect, auto visit) {
    return VisitWithBranches(regions, layout, rect, visit);
  });
}
BENCHMARK(BM_WarmAnswerControl);

// The server's path: VisitPoints into the packed arrays (get_points_rpc.cc).
void BM_WarmAnswer(benchmark::State& state) {
  TimeWarmAnswers(state, [](const auto& regions, const auto& layout, const Rect& rect, auto visit) {
    return VisitPoints(regions, layout, rect, 0, SIZE_MAX, visit);
  });
}
BENCHMARK(BM_WarmAnswer);

}  // namespace
}  // namespace scallop

BENCHMARK_MAIN();
