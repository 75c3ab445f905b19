// FieldPointGrid against brute force: AnyNear visits every point inside the window once (the
// occupancy bits must not hide a cell), including windows wider than 64 columns, points beyond
// the area (filed in edge cells), points packed and added after packing, and early stops;
// Conflicts agrees with testing every point.
#include "scallop/sampling/field_point_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
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
