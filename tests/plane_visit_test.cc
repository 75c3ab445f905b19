// PlaneEngine::Regions, CachedRegions and VisitPoints (the copy-once path the
// server pages from) against a brute-force filter of the same regions.
#include <gtest/gtest.h>

#include "scallop/plane/plane_engine.h"
#include "scallop/random/rng.h"
#include "tests/test_worlds.h"

namespace scallop {
namespace {

struct Slice {
  std::vector<Vec2> positions;
  std::vector<uint64_t> ids;
};

// Every point of every region tested against the rectangle, in query order.
Slice BruteForce(const std::vector<RegionHandle>& regions, const Rect& rect) {
  Slice all;
  for (const RegionHandle& region : regions) {
    for (size_t k = 0; k < region->points.size(); ++k) {
      if (!rect.Contains(region->points[k])) continue;
      all.positions.push_back(region->points[k]);
      all.ids.push_back(EncodePointId(region->key, static_cast<uint32_t>(k)));
    }
  }
  return all;
}

TEST(PlaneVisitTest, PagesEqualSlicesOfTheBruteForceOrder) {
  PlaneEngine engine({.threads = 1});
  Rng rng(77);
  for (int trial = 0; trial < 40; ++trial) {
    const World world = ValidWorld({.seed = rng.NextBits(), .min_distance = rng.Uniform(0.1, 3)});
    const double d = world.min_distance();
    const double x = rng.Uniform(-500, 500) * d, y = rng.Uniform(-500, 500) * d;
    // From a sliver inside one region to rectangles holding whole regions.
    const Rect rect{x, y, x + rng.Uniform(0.5, 70) * d, y + rng.Uniform(0.5, 70) * d};
    StatusOr<std::vector<RegionHandle>> regions = engine.Regions(world, rect);
    ASSERT_TRUE(regions.ok()) << regions.status().message();
    const Slice expected = BruteForce(*regions, rect);
    const size_t total = expected.ids.size();
    const size_t begin = rng.Below(total + 2), end = begin + rng.Below(total + 2);
    Slice got;
    const size_t counted =
        VisitPoints(*regions, RegionLayout(d), rect, begin, end, [&](const Vec2& p, uint64_t id) {
          got.positions.push_back(p);
          got.ids.push_back(id);
        });
    EXPECT_EQ(counted, total);
    const size_t from = std::min(begin, total), to = std::min(end, total);
    EXPECT_EQ(got.ids,
              std::vector<uint64_t>(expected.ids.begin() + from, expected.ids.begin() + to));
    EXPECT_EQ(got.positions, std::vector<Vec2>(expected.positions.begin() + from,
                                               expected.positions.begin() + to));
    StatusOr<PlanePoints> points = engine.Points(world, rect);
    ASSERT_TRUE(points.ok());
    EXPECT_EQ(points->ids, expected.ids);
  }
}

// Whole pages take the branch-free filter for every region the rectangle
// cuts (VisitPointsInside); its edges are put on points' own coordinates,
// so the half-open rule ([x0, x1) x [y0, y1)) decides points on them.
TEST(PlaneVisitTest, WholePagesKeepExactlyThePointsOfTheHalfOpenRectangle) {
  PlaneEngine engine({.threads = 1});
  Rng rng(78);
  int on_edges = 0;  // points lying on the rectangles' edges, kept or not
  for (int trial = 0; trial < 40; ++trial) {
    const World world = ValidWorld({.seed = rng.NextBits(), .min_distance = rng.Uniform(0.1, 3)});
    const double d = world.min_distance();
    const Vec2 corner{rng.Uniform(-500, 500) * d, rng.Uniform(-500, 500) * d};
    const Vec2 size{rng.Uniform(0.5, 70) * d, rng.Uniform(0.5, 70) * d};
    StatusOr<PlanePoints> around =
        engine.Points(world, {corner.x, corner.y, corner.x + size.x, corner.y + size.y});
    ASSERT_TRUE(around.ok()) << around.status().message();
    ASSERT_GE(around->positions.size(), 2u) << "trial " << trial;
    // Edges through two of the rectangle's points: x0 and y0 from one, x1 and y1 from another.
    const Vec2 low = around->positions[rng.Below(around->positions.size())];
    const Vec2 high = around->positions[rng.Below(around->positions.size())];
    const Rect rect{std::min(low.x, high.x), std::min(low.y, high.y),
                    std::max(low.x, high.x) + (low.x == high.x ? d : 0),
                    std::max(low.y, high.y) + (low.y == high.y ? d : 0)};
    StatusOr<std::vector<RegionHandle>> regions = engine.Regions(world, rect);
    ASSERT_TRUE(regions.ok()) << regions.status().message();
    const Slice expected = BruteForce(*regions, rect);
    Slice got;
    const size_t counted =
        VisitPoints(*regions, RegionLayout(d), rect, 0, SIZE_MAX, [&](const Vec2& p, uint64_t id) {
          got.positions.push_back(p);
          got.ids.push_back(id);
        });
    EXPECT_EQ(counted, expected.ids.size()) << "trial " << trial;
    EXPECT_EQ(got.ids, expected.ids) << "trial " << trial;
    EXPECT_EQ(got.positions, expected.positions) << "trial " << trial;
    // The same through a visitor that takes whole regions as runs.
    Slice in_runs;
    struct {
      Slice& slice;
      void operator()(const Vec2& p, uint64_t id) const {
        slice.positions.push_back(p);
        slice.ids.push_back(id);
      }
      void operator()(const Vec2* run, size_t count, uint64_t first_id) const {
        for (size_t k = 0; k < count; ++k) (*this)(run[k], first_id + k);
      }
    } visit_runs{in_runs};
    EXPECT_EQ(VisitPoints(*regions, RegionLayout(d), rect, 0, SIZE_MAX, visit_runs), counted);
    EXPECT_EQ(in_runs.ids, expected.ids) << "trial " << trial;
    EXPECT_EQ(in_runs.positions, expected.positions) << "trial " << trial;
    for (const RegionHandle& region : *regions) {
      for (const Vec2& p : region->points) {
        on_edges += p.x == rect.x0 || p.x == rect.x1 || p.y == rect.y0 || p.y == rect.y1;
      }
    }
  }
  EXPECT_GE(on_edges, 40);  // the edges were tested, not only the insides
}

TEST(PlaneVisitTest, CachedRegionsNeverGenerates) {
  PlaneEngine engine({.threads = 1});
  const World world = ValidWorld({.seed = 3});
  const Rect rect{-20, -20, 20, 20};
  EXPECT_FALSE(engine.CachedRegions(world, rect).has_value());
  EXPECT_EQ(engine.CacheStats().misses, 0);
  EXPECT_EQ(engine.CacheStats().regions, 0);
  StatusOr<std::vector<RegionHandle>> regions = engine.Regions(world, rect);
  ASSERT_TRUE(regions.ok());
  const int64_t misses = engine.CacheStats().misses;
  std::optional<std::vector<RegionHandle>> cached = engine.CachedRegions(world, rect);
  ASSERT_TRUE(cached.has_value());
  EXPECT_EQ(*cached, *regions);  // the very same shared regions
  EXPECT_EQ(engine.CacheStats().misses, misses);
  // One region short (a wider rectangle) is not enough.
  EXPECT_FALSE(engine.CachedRegions(world, {-20, -20, 60, 20}).has_value());
}

}  // namespace
}  // namespace scallop
