// A3's fast parts against their plain twins, and A3's output pinned. The
// neighbour gathers (PointGrid's, BoundaryGrid's tiled one) and the two-lane
// pseudo-angles must give what PointGrid::ForEachNear with the distance test
// and PseudoAngle give; and
// SampleBoundary must give the bits it gave before they were written, so a
// speed-up that moves a point, reorders points or changes the random draws
// fails here, on bounded domains and tori too, not only in the plane's
// golden test.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "scallop/random/rng.h"
#include "scallop/sampling/available_boundary.h"
#include "scallop/sampling/boundary_grid.h"
#include "scallop/sampling/boundary_sampler.h"
#include "scallop/sampling/point_grid.h"

namespace scallop {
namespace {

// The two lanes' results against PseudoAngle's, bit for bit except that a
// zero key may lose its sign (keys are only compared).
void ExpectSameKeys(Vec2 a, Vec2 b) {
  const Doubles keys = PseudoAngles(Doubles{a.x, b.x}, Doubles{a.y, b.y});
  const Vec2 directions[2] = {a, b};
  for (int lane = 0; lane < 2; ++lane) {
    const Vec2 v = directions[lane];
    const double expected = PseudoAngle(v);
    if (expected == 0.0) {
      EXPECT_EQ(keys[lane], 0.0) << v.x << "," << v.y;
    } else {
      EXPECT_EQ(std::bit_cast<uint64_t>(keys[lane]), std::bit_cast<uint64_t>(expected))
          << std::hexfloat << v.x << "," << v.y << ": " << keys[lane] << " vs " << expected;
    }
  }
}

TEST(BoundarySamplerPartsTest, PseudoAnglesMatchPseudoAngle) {
  // The axes, signed zeros and quadrant edges, where the selects change.
  const Vec2 edges[] = {{1, 0},     {0, 1},    {-1, 0},      {0, -1},     {-0.0, 1},
                        {-0.0, -1}, {1, -0.0}, {-1, -0.0},   {1, 1},      {-1, 1},
                        {-1, -1},   {1, -1},   {3, -1e-300}, {-1e-300, 3}};
  for (const Vec2 a : edges) {
    for (const Vec2 b : edges) ExpectSameKeys(a, b);
  }
  Rng dice(HashWords({41}));
  for (int trial = 0; trial < 200000; ++trial) {
    // Magnitudes from 2^-40 to 2^40, and a few near-axis directions.
    const double scale = std::ldexp(1.0, static_cast<int>(dice.Below(81)) - 40);
    Vec2 a{scale * dice.Uniform(-1, 1), scale * dice.Uniform(-1, 1)};
    Vec2 b{dice.Uniform(-1, 1), dice.Uniform(-1, 1)};
    if (trial % 7 == 0) a.y *= 1e-17;
    if (trial % 11 == 0) b.x *= 1e-17;
    ExpectSameKeys(a, b);
  }
}

// Points at least d apart in `domain`, from A3 itself.
std::vector<Vec2> SpacedPoints(const Domain& domain, double d, uint64_t seed) {
  SamplingProblem problem;
  problem.domain = domain;
  problem.min_distance = d;
  Rng rng(seed);
  return SampleBoundary(problem, rng);
}

TEST(BoundarySamplerPartsTest, GatherNearMatchesForEachNearAndTheDistanceTest) {
  Rng dice(HashWords({42}));
  for (int trial = 0; trial < 16; ++trial) {
    const bool torus = trial % 2 == 1;
    const double d = dice.Uniform(0.5, 2.0);
    const double x0 = dice.Uniform(-50, 50), y0 = dice.Uniform(-50, 50);
    const Domain domain{{x0, y0, x0 + d * dice.Uniform(8, 30), y0 + d * dice.Uniform(8, 30)},
                        torus};
    SCOPED_TRACE(::testing::Message() << "trial " << trial << " torus " << torus);
    const std::vector<Vec2> points = SpacedPoints(domain, d, dice.NextBits());
    PointGrid grid(domain.rect, torus, d, torus ? 0.0 : 3 * d);
    for (size_t i = 0; i < points.size(); ++i) grid.Insert(static_cast<int32_t>(i), points[i]);
    std::vector<Vec2> gathered;
    for (int query = 0; query < 300; ++query) {
      // Stored points (which must not see themselves) and arbitrary spots.
      const bool stored = query % 2 == 0;
      const auto self = static_cast<int32_t>(dice.Below(points.size()));
      const Vec2 p = stored ? points[static_cast<size_t>(self)]
                            : Vec2{dice.Uniform(domain.rect.x0, domain.rect.x1),
                                   dice.Uniform(domain.rect.y0, domain.rect.y1)};
      const double radius = dice.Uniform(1.0, 2.2) * d;
      const double limit_squared = radius * radius * dice.Uniform(0.5, 1.0);
      std::vector<Vec2> expected;
      grid.ForEachNear(p, radius, [&](int32_t index, Vec2 q) {
        if ((!stored || index != self) && SquaredLength(q - p) < limit_squared)
          expected.push_back(q);
      });
      const size_t count = grid.GatherNear(p, radius, limit_squared, stored ? self : -1, gathered);
      ASSERT_EQ(count, expected.size()) << "query " << query;
      for (size_t k = 0; k < count; ++k) {
        EXPECT_EQ(gathered[k], expected[k]) << "query " << query << " neighbour " << k;
      }
    }
  }
}

// BoundaryGrid, A3's tiled grid for rectangles, must gather what PointGrid
// gathers: the same positions (in its own cells' order: A3 does not depend
// on the order), on grids of many tiles and of one, near the edges and with
// cells on both sides of a tile's edge. Odd trials reuse one grid, Reset to
// the trial's domain from the last odd trial's (larger or smaller), filled
// with other points there and Reset again, as a plane region's run reuses
// the grid of the run before it.
// The first `count` positions of `points`, sorted by x, then y.
std::vector<Vec2> Sorted(const std::vector<Vec2>& points, size_t count) {
  std::vector<Vec2> sorted(points.begin(), points.begin() + static_cast<std::ptrdiff_t>(count));
  std::sort(sorted.begin(), sorted.end(),
            [](Vec2 a, Vec2 b) { return a.x != b.x ? a.x < b.x : a.y < b.y; });
  return sorted;
}

TEST(BoundarySamplerPartsTest, BoundaryGridGathersWhatPointGridGathers) {
  Rng dice(HashWords({43}));
  BoundaryGrid reused({0, 0, 1, 1}, 1.0, 0.0);
  for (int trial = 0; trial < 24; ++trial) {
    const double d = dice.Uniform(0.3, 2.0);
    const double x0 = dice.Uniform(-50, 50), y0 = dice.Uniform(-50, 50);
    const double sides = trial % 4 == 0 ? dice.Uniform(1, 4) : dice.Uniform(8, 40);
    const Domain domain{{x0, y0, x0 + d * sides, y0 + d * dice.Uniform(1, 40)}, false};
    SCOPED_TRACE(::testing::Message() << "trial " << trial);
    const std::vector<Vec2> points = SpacedPoints(domain, d, dice.NextBits());
    const double margin = dice.Uniform(0, 3) * d;
    PointGrid plain(domain.rect, false, d, margin);
    BoundaryGrid fresh(domain.rect, d, margin);
    if (trial % 2 == 1) {
      // Filled with other points of the same domain first: a cell left as it was would
      // hand its stale point to a query right there.
      reused.Reset(domain.rect, d, margin);
      const std::vector<Vec2> others = SpacedPoints(domain, d, dice.NextBits());
      for (size_t i = 0; i < others.size(); ++i) reused.Insert(static_cast<int32_t>(i), others[i]);
      reused.Reset(domain.rect, d, margin);
    }
    BoundaryGrid& tiled = trial % 2 == 1 ? reused : fresh;
    for (size_t i = 0; i < points.size(); ++i) {
      plain.Insert(static_cast<int32_t>(i), points[i]);
      tiled.Insert(static_cast<int32_t>(i), points[i]);
    }
    std::vector<Vec2> expected, gathered;
    for (int query = 0; query < 300; ++query) {
      // Stored points (which must not see themselves) and spots in the grown domain.
      const bool stored = query % 2 == 0;
      const auto self = static_cast<int32_t>(dice.Below(points.size()));
      const Vec2 p = stored ? points[static_cast<size_t>(self)]
                            : Vec2{dice.Uniform(domain.rect.x0 - margin, domain.rect.x1 + margin),
                                   dice.Uniform(domain.rect.y0 - margin, domain.rect.y1 + margin)};
      // Up to 8 x 8 cells (bits gathered first) and wider (every cell read).
      const double radius = dice.Uniform(0.5, 3.5) * d;
      const double limit_squared = radius * radius * dice.Uniform(0.5, 1.0);
      const size_t count = plain.GatherNear(p, radius, limit_squared, stored ? self : -1, expected);
      ASSERT_EQ(tiled.GatherNear(p, radius, limit_squared, stored ? self : -1, gathered), count)
          << "query " << query;
      EXPECT_EQ(Sorted(gathered, count), Sorted(expected, count)) << "query " << query;
    }
  }
}

// A grid of more than 4 MiB, whose positions come from HugePageAllocator's
// aligned, huge-page path: the same gathers, and (under ASan) a clean free.
TEST(BoundarySamplerPartsTest, LargeBoundaryGridGathersWhatPointGridGathers) {
  const Domain domain{{-300, -200, 300, 200}, false};
  const std::vector<Vec2> points = SpacedPoints(domain, 1.0, 44);
  PointGrid plain(domain.rect, false, 1.0, 3.0);
  BoundaryGrid tiled(domain.rect, 1.0, 3.0);
  ASSERT_TRUE(HugePageAllocator<Vec2>::Large(plain.cell_count()));
  for (size_t i = 0; i < points.size(); ++i) {
    plain.Insert(static_cast<int32_t>(i), points[i]);
    tiled.Insert(static_cast<int32_t>(i), points[i]);
  }
  std::vector<Vec2> expected, gathered;
  for (size_t i = 0; i < points.size(); i += 97) {
    const auto self = static_cast<int32_t>(i);
    const size_t count = plain.GatherNear(points[i], 2.0, 4.0, self, expected);
    ASSERT_EQ(tiled.GatherNear(points[i], 2.0, 4.0, self, gathered), count) << i;
    EXPECT_EQ(Sorted(gathered, count), Sorted(expected, count)) << i;
  }
}

// A run's points, unprocessed flags and next random number, hashed.
uint64_t RunHash(const SamplingProblem& problem, uint64_t seed) {
  Rng rng(seed);
  std::vector<bool> unprocessed;
  const std::vector<Vec2> points = SampleBoundary(problem, rng, &unprocessed);
  uint64_t h = HashWords({points.size()});
  for (const Vec2& p : points) {
    h = HashWords({h, std::bit_cast<uint64_t>(p.x), std::bit_cast<uint64_t>(p.y)});
  }
  for (const bool u : unprocessed) h = HashWords({h, u});
  return HashWords({h, rng.NextBits()});
}

// Pinned on the generator as of version 3 (A3 draws by pseudo-angle with
// rejection; version 2 drew angles through atan2 and sincos). A change here
// changes worlds: see docs/design.md, "Generator versions".
TEST(BoundarySamplerPartsTest, OutputIsPinned) {
  SamplingProblem rectangle;
  rectangle.domain.rect = {-13.7, 5.2, 60, 30};
  rectangle.min_distance = 0.37;
  EXPECT_EQ(RunHash(rectangle, 9), 0x84b54eaba7a8ef61u) << std::hex << RunHash(rectangle, 9);

  SamplingProblem torus;
  torus.domain = {{0, 0, 100, 120}, true};
  EXPECT_EQ(RunHash(torus, 12), 0x076ce52fa9ad5c3du) << std::hex << RunHash(torus, 12);

  // As the plane poses it: fixed and inert points from a neighbour, its
  // rectangle covered, a stop rectangle and a seed area.
  SamplingProblem first;
  first.domain.rect = {0, 0, 30, 30};
  Rng first_rng(21);
  const std::vector<Vec2> earlier = SampleBoundary(first, first_rng);
  SamplingProblem plane;
  plane.domain.rect = {20, 0, 50, 30};
  std::vector<Vec2> fixed, inert;
  for (const Vec2& q : earlier) {
    if (SquaredDistance(plane.domain.rect, q) >= 4.0) continue;
    (q.x > 26 ? fixed : inert).push_back(q);
  }
  const std::vector<Rect> covered{{0, 0, 27, 30}};
  plane.fixed_points = fixed;
  plane.inert_points = inert;
  plane.covered_rects = covered;
  plane.stop_when_covered = Rect{30, 5, 40, 25};
  plane.seed_area = Rect{44, 14, 45, 15};
  EXPECT_EQ(RunHash(plane, 26), 0xe67c889034303f39u) << std::hex << RunHash(plane, 26);
}

}  // namespace
}  // namespace scallop
