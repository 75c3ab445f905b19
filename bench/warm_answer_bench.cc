// What a warm GetPoints costs scallopd before gRPC takes over: random 64 d
// tiles of a warm 256 d square (the load benchmark's warm mode), their cached
// regions' points copied into a Points message as AnswerGetPoints does it,
// beside a control from the same run.
//
//   build/bench/warm_answer_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <grpcpp/impl/codegen/proto_utils.h>

#include <vector>

#include "encoded_points.h"
#include "scallop/plane/plane_engine.h"
#include "scallop/random/rng.h"
#include "server/packed_answer.h"
#include "world_messages.h"

namespace scallop {
namespace {

constexpr double kTile = 64;        // d, as load_generator --tile
constexpr double kWarmSide = 256;   // d, as load_generator --warm-side
constexpr int kTilesPerPass = 256;  // distinct tiles, so the regions are not all in L1

// The load benchmark's world: scallopd's default.
World WarmWorld() { return *World::Create({.seed = 1}); }

struct WarmTiles {
  PlaneEngine engine{{.threads = 1}};
  World world = WarmWorld();
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

// Each pass: `answer(regions, layout, rect, upper_bound)` of every tile, which returns the
// points it answered with; upper_bound is the points of the tile's regions.
template <typename Answer>
void TimeWarmTiles(benchmark::State& state, Answer answer) {
  WarmTiles tiles;
  const RegionLayout layout(tiles.world);
  int64_t points = 0;
  for (auto _ : state) {
    for (int k = 0; k < kTilesPerPass; ++k) {
      const std::vector<RegionHandle>& regions = tiles.regions[static_cast<size_t>(k)];
      size_t upper_bound = 0;
      for (const RegionHandle& region : regions) upper_bound += region->points.size();
      points += static_cast<int64_t>(
          answer(regions, layout, tiles.rects[static_cast<size_t>(k)], upper_bound));
    }
  }
  SetPointsPerSecond(state, points);
}

// Each pass: every tile's points through `visit_points` into a packed Points message.
template <typename VisitPointsOf>
void TimeWarmAnswers(benchmark::State& state, VisitPointsOf visit_points) {
  const World world = WarmWorld();
  TimeWarmTiles(state, [&](const auto& regions, const RegionLayout& layout, const Rect& rect,
                           size_t upper_bound) {
    v1::Points message;
    size_t points = 0;
    WritePoints(message, PointEncoding::kPacked, world, upper_bound, [&](auto& appender) {
      points = visit_points(regions, layout, rect,
                            [&](const Vec2& p, uint64_t id) { appender.Append(p, id); });
    });
    benchmark::DoNotOptimize(message.xs().data());
    return points;
  });
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

// The answer's bytes as gRPC sends them, the way scallopd made them before the packed answer:
// the copy above into a GetPointsResponse with its world, serialized by protobuf.
void BM_WarmAnswerBytesThroughMessage(benchmark::State& state) {
  const World world = WarmWorld();
  const v1::World world_message = WorldToMessage(world);
  TimeWarmTiles(state, [&](const auto& regions, const RegionLayout& layout, const Rect& rect,
                           size_t upper_bound) {
    v1::GetPointsResponse response;
    size_t points = 0;
    WritePoints(*response.mutable_points(), PointEncoding::kPacked, world, upper_bound,
                [&](auto& appender) {
                  points = VisitPoints(regions, layout, rect, 0, SIZE_MAX,
                                       [&](const Vec2& p, uint64_t id) { appender.Append(p, id); });
                });
    *response.mutable_world() = world_message;
    grpc::ByteBuffer bytes;
    bool own = false;
    benchmark::DoNotOptimize(
        grpc::SerializationTraits<v1::GetPointsResponse>::Serialize(response, &bytes, &own));
    return points;
  });
}
BENCHMARK(BM_WarmAnswerBytesThroughMessage);

// The same bytes written straight into gRPC's slices (server/packed_answer.h), as scallopd does.
void BM_WarmAnswerBytesPacked(benchmark::State& state) {
  const std::string world_message = WorldToMessage(WarmWorld()).SerializeAsString();
  TimeWarmTiles(state, [&](const auto& regions, const RegionLayout& layout, const Rect& rect,
                           size_t upper_bound) {
    server::PackedAnswerWriter writer(upper_bound);
    const server::AppendTo<server::PackedAnswerWriter> visit{writer};
    const size_t points = VisitPoints(regions, layout, rect, 0, SIZE_MAX, visit);
    grpc::ByteBuffer bytes = writer.Finish("", world_message);
    benchmark::DoNotOptimize(bytes);
    return points;
  });
}
BENCHMARK(BM_WarmAnswerBytesPacked);

// The same writer in its two-lane (SSE2) loops, as scallopd ran before the
// four-lane ones, and still does on a CPU without AVX2.
void BM_WarmAnswerBytesPackedTwoLanes(benchmark::State& state) {
  const std::string world_message = WorldToMessage(WarmWorld()).SerializeAsString();
  TimeWarmTiles(state, [&](const auto& regions, const RegionLayout& layout, const Rect& rect,
                           size_t upper_bound) {
    server::PackedAnswerWriter writer(upper_bound, server::CopyLanes::kTwoLanes);
    const server::AppendTo<server::PackedAnswerWriter> visit{writer};
    const size_t points = VisitPoints(regions, layout, rect, 0, SIZE_MAX, visit);
    grpc::ByteBuffer bytes = writer.Finish("", world_message);
    benchmark::DoNotOptimize(bytes);
    return points;
  });
}
BENCHMARK(BM_WarmAnswerBytesPackedTwoLanes);

}  // namespace
}  // namespace scallop

BENCHMARK_MAIN();
