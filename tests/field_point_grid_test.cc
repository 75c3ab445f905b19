// FieldPointGrid against brute force: AnyNear visits every point inside the window once (the
// listed bits must not hide a cell, a row's packed run must not stop short), including windows
// wider than 64 columns, points beyond the area (filed in edge cells), points packed and added
// after packing, and early stops, in the order the field sampler's bits depend on; Conflicts
// agrees with testing every point.
#include "scallop/sampling/field_point_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "scallop/random/rng.h"

namespace scallop {
namespace {

TEST(FieldPointGridTest, AnyNearVisitsEveryPointInTheWindowOnce) {
  int64_t missed = 0;
  int64_t repeated = 0;
  int64_t windows = 0;
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    Rng rng(HashWords({seed, 0x67726964}));
    const double cell = rng.Uniform(0.3, 3.0);
    const Rect area{rng.Uniform(-100, 0), rng.Uniform(-100, 0), rng.Uniform(1, 400),
                    rng.Uniform(1, 100)};
    FieldPointGrid grid(area, cell);
    const int n = 200 + static_cast<int>(rng.Below(2000));
    // Packed once partway (or, for some seeds, twice, or never), as the field sampler does.
    const int pack_at = seed % 4 == 0 ? -1 : static_cast<int>(rng.Below(static_cast<uint64_t>(n)));
    for (int k = 0; k < n; ++k) {
      if (k == pack_at || (seed % 4 == 1 && k == n - 1)) grid.Pack();
      // One in ten beyond the area, which the grid files in its edge cells.
      const Rect where = rng.Below(10) == 0 ? Grown(area, 20.0) : area;
      grid.Add({rng.Uniform(where.x0, where.x1), rng.Uniform(where.y0, where.y1)},
               rng.Uniform(0.1, 5.0));
    }
    const std::vector<FieldPoint>& points = grid.points();
    // A visited point may be a packed copy: it is known by its position (all distinct here).
    std::map<std::pair<double, double>, size_t> index_of;
    for (size_t k = 0; k < points.size(); ++k) index_of[{points[k].p.x, points[k].p.y}] = k;
    ASSERT_EQ(index_of.size(), points.size());
    for (int w = 0; w < 200; ++w, ++windows) {
      const Vec2 c{rng.Uniform(area.x0 - 30, area.x1 + 30),
                   rng.Uniform(area.y0 - 30, area.y1 + 30)};
      // Up to 300 cells wide: several 64-column words a row.
      const Rect window{c.x, c.y, c.x + rng.Uniform(0.0, 300.0 * cell),
                        c.y + rng.Uniform(0.0, 10.0 * cell)};
      std::vector<int> seen(points.size(), 0);
      grid.AnyNear(window, [&](const FieldPoint& q) {
        const auto found = index_of.find({q.p.x, q.p.y});
        EXPECT_TRUE(found != index_of.end() && points[found->second].r == q.r);
        if (found != index_of.end()) ++seen[found->second];
        return false;
      });
      for (size_t k = 0; k < points.size(); ++k) {
        const Vec2 p = points[k].p;
        const bool inside =
            window.x0 <= p.x && p.x <= window.x1 && window.y0 <= p.y && p.y <= window.y1;
        if (inside && seen[k] == 0) ++missed;
        if (seen[k] > 1) ++repeated;
      }
    }
  }
  EXPECT_EQ(missed, 0) << "of " << windows << " windows";
  EXPECT_EQ(repeated, 0);
}

// The order AnyNear promises, computed from the points alone: the window's cells row by row
// from the bottom, each row by column; in a cell, the points added before the last Pack in the
// order they were added, then the later ones, newest first. Cells are floor((v - v0) / cell)
// clamped to the grid, as the grid files them.
std::vector<size_t> ExpectedOrder(const std::vector<FieldPoint>& points, size_t packed,
                                  const Rect& area, double cell, const Rect& window) {
  const auto columns = static_cast<int64_t>(std::ceil(area.Width() / cell));
  const auto rows = static_cast<int64_t>(std::ceil(area.Height() / cell));
  const auto index = [&](double v, double v0, int64_t count) {
    return std::clamp<int64_t>(static_cast<int64_t>(std::floor((v - v0) / cell)), 0, count - 1);
  };
  const int64_t c0 = index(window.x0, area.x0, columns);
  const int64_t c1 = index(window.x1, area.x0, columns);
  const int64_t r0 = index(window.y0, area.y0, rows);
  const int64_t r1 = index(window.y1, area.y0, rows);
  std::vector<size_t> order;
  for (int64_t row = r0; row <= r1; ++row) {
    for (int64_t col = c0; col <= c1; ++col) {
      const auto in_cell = [&](size_t k) {
        return index(points[k].p.x, area.x0, columns) == col &&
               index(points[k].p.y, area.y0, rows) == row;
      };
      for (size_t k = 0; k < packed; ++k) {
        if (in_cell(k)) order.push_back(k);
      }
      for (size_t k = points.size(); k > packed; --k) {
        if (in_cell(k - 1)) order.push_back(k - 1);
      }
    }
  }
  return order;
}

TEST(FieldPointGridTest, AnyNearVisitsInTheOrderTheSamplerDependsOn) {
  int64_t windows = 0;
  for (uint64_t seed = 1; seed <= 12; ++seed) {
    Rng rng(HashWords({seed, 0x6f72646572}));
    const double cell = rng.Uniform(0.5, 2.0);
    const Rect area{0, 0, rng.Uniform(20, 150), rng.Uniform(20, 60)};
    FieldPointGrid grid(area, cell);
    // Dense enough that cells hold several points, some packed and some listed.
    const int n = 1000 + static_cast<int>(rng.Below(2000));
    const int pack_at = seed % 3 == 0 ? -1 : static_cast<int>(rng.Below(static_cast<uint64_t>(n)));
    size_t packed = 0;
    for (int k = 0; k < n; ++k) {
      if (k == pack_at) {
        grid.Pack();
        packed = static_cast<size_t>(k);
      }
      grid.Add({rng.Uniform(area.x0, area.x1), rng.Uniform(area.y0, area.y1)},
               rng.Uniform(0.1, 3.0));
    }
    const std::vector<FieldPoint>& points = grid.points();
    std::map<std::pair<double, double>, size_t> index_of;
    for (size_t k = 0; k < points.size(); ++k) index_of[{points[k].p.x, points[k].p.y}] = k;
    for (int w = 0; w < 100; ++w, ++windows) {
      const Vec2 c{rng.Uniform(area.x0 - 5, area.x1 + 5), rng.Uniform(area.y0 - 5, area.y1 + 5)};
      const Rect window{c.x, c.y, c.x + rng.Uniform(0.0, 80.0 * cell),
                        c.y + rng.Uniform(0.0, 8.0 * cell)};
      std::vector<size_t> seen;
      grid.AnyNear(window, [&](const FieldPoint& q) {
        seen.push_back(index_of.at({q.p.x, q.p.y}));
        return false;
      });
      ASSERT_EQ(seen, ExpectedOrder(points, packed, area, cell, window))
          << "seed " << seed << ", window " << w;
    }
  }
  EXPECT_EQ(windows, 1200);
}

TEST(FieldPointGridTest, ConflictsAgreesWithEveryPointAndStopsEarly) {
  Rng rng(5);
  const Rect area{0, 0, 200, 150};
  FieldPointGrid grid(area, 2.0);
  for (int k = 0; k < 3000; ++k) {
    grid.Add({rng.Uniform(0, 200), rng.Uniform(0, 150)}, rng.Uniform(0.5, 4.0));
  }
  int64_t disagreements = 0;
  int64_t conflicts = 0;
  for (int k = 0; k < 5000; ++k) {
    const Vec2 x{rng.Uniform(0, 200), rng.Uniform(0, 150)};
    const double rx = rng.Uniform(0.5, 4.0);
    bool brute = false;
    for (const FieldPoint& q : grid.points()) {
      const double dx = x.x - q.p.x;
      const double dy = x.y - q.p.y;
      const double m = std::max(rx, q.r);
      brute = brute || dx * dx + dy * dy < m * m;
    }
    // Reach 4: no point's R exceeds it here, so no conflict lies farther.
    disagreements += grid.Conflicts(x, rx, 4.0) != brute ? 1 : 0;
    conflicts += brute ? 1 : 0;
  }
  EXPECT_EQ(disagreements, 0);
  EXPECT_GT(conflicts, 100);  // both answers were exercised
  int visits = 0;
  EXPECT_TRUE(grid.AnyNear(area, [&](const FieldPoint&) { return ++visits == 3; }));
  EXPECT_EQ(visits, 3);
}

}  // namespace
}  // namespace scallop
