// The brute-force twin of NearestLookup for tests: every point of a 12 d
// square about the position (from PlaneEngine::Points), sorted by
// (squared distance, id). Slow and obviously right; on a maximal world the
// two nearest always lie within 2 d, well inside the square. With the bitwise
// comparison of two answers and a batch asked from two threads at once.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <span>
#include <thread>
#include <tuple>
#include <vector>

#include "scallop/noise/cell_value.h"
#include "scallop/noise/nearest_lookup.h"
#include "scallop/plane/plane_engine.h"

namespace scallop::testing {

// Every point of `points` as (dx*dx + dy*dy, id, point) about p, sorted by (squared, id).
inline std::vector<std::tuple<double, uint64_t, Vec2>> SortedByKey(Vec2 p,
                                                                   const PlanePoints& points) {
  std::vector<std::tuple<double, uint64_t, Vec2>> all;
  for (size_t k = 0; k < points.positions.size(); ++k) {
    const Vec2 q = points.positions[k];
    const double dx = p.x - q.x, dy = p.y - q.y;
    all.emplace_back(dx * dx + dy * dy, points.ids[k], q);
  }
  std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) {
    return std::tie(std::get<0>(a), std::get<1>(a)) < std::tie(std::get<0>(b), std::get<1>(b));
  });
  return all;
}

inline NearestPoint OracleNearest(PlaneEngine& engine, const World& world, Vec2 p) {
  const double d = world.min_distance(), half = 6 * d;
  const double limit = RegionLayout(d).precision_limit();
  const Rect square{std::max(p.x - half, -limit), std::max(p.y - half, -limit),
                    std::min(p.x + half, limit), std::min(p.y + half, limit)};
  StatusOr<PlanePoints> points = engine.Points(world, square);
  EXPECT_TRUE(points.ok()) << points.status().message();
  const std::vector<std::tuple<double, uint64_t, Vec2>> all = SortedByKey(p, *points);
  EXPECT_GE(all.size(), 2u) << "at (" << p.x << ", " << p.y << ")";
  if (all.size() < 2) return {};
  // The answer must be certain: the second nearest well inside the square.
  EXPECT_LT(std::sqrt(std::get<0>(all[1])), half - d);
  return {.id = std::get<1>(all[0]),
          .position = std::get<2>(all[0]),
          .f1 = std::sqrt(std::get<0>(all[0])),
          .f2 = std::sqrt(std::get<0>(all[1])),
          .second_id = std::get<1>(all[1]),
          .cell_value = CellValue(std::get<1>(all[0]))};
}

inline bool SameBits(double a, double b) {
  return std::bit_cast<uint64_t>(a) == std::bit_cast<uint64_t>(b);
}

// Every field equal, doubles to the bit.
inline ::testing::AssertionResult SameNearest(const NearestPoint& expected,
                                              const NearestPoint& actual) {
  if (expected.id == actual.id && expected.second_id == actual.second_id &&
      SameBits(expected.position.x, actual.position.x) &&
      SameBits(expected.position.y, actual.position.y) && SameBits(expected.f1, actual.f1) &&
      SameBits(expected.f2, actual.f2) && SameBits(expected.cell_value, actual.cell_value)) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure()
         << std::hexfloat << "expected id " << expected.id << " (second " << expected.second_id
         << ") f1 " << expected.f1 << " f2 " << expected.f2 << "; got id " << actual.id
         << " (second " << actual.second_id << ") f1 " << actual.f1 << " f2 " << actual.f2;
}

// `lookup`'s answers for `positions` from two threads at once, each asking half the batch (as
// scallopd's calls share one lookup); a failed call fails the test.
inline std::vector<NearestPoint> NearestOnTwoThreads(NearestLookup& lookup, const World& world,
                                                     std::span<const Vec2> positions) {
  std::vector<NearestPoint> results(positions.size());
  const size_t middle = positions.size() / 2;
  std::thread other([&] {
    EXPECT_TRUE(
        lookup.Nearest(world, positions.subspan(middle), std::span(results).subspan(middle)).ok());
  });
  EXPECT_TRUE(
      lookup.Nearest(world, positions.first(middle), std::span(results).first(middle)).ok());
  other.join();
  return results;
}

}  // namespace scallop::testing
