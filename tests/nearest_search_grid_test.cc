// NearestSearchGrid on synthetic point sets, where the oracle is a plain
// scan of the same set: exact ties on an integer lattice (broken by the
// smaller id), and sparse random subsets, where the grid must either give
// the exact answer or refuse to certify one.
#include "scallop/noise/nearest_search_grid.h"

#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

#include "scallop/noise/cell_value.h"
#include "scallop/random/rng.h"

namespace scallop {

// For test names: "kTwoLanes" rather than the enum's bytes.
void PrintTo(NearestSearchGrid::FirstPassWidth width, std::ostream* out) {
  *out << (width == NearestSearchGrid::FirstPassWidth::kTwoLanes ? "kTwoLanes" : "kWidest");
}

namespace {

struct PointSet {
  std::vector<Vec2> points;
  std::vector<uint64_t> ids;
};

TwoNearest ScanAll(const PointSet& set, Vec2 p) {
  TwoNearest best;
  for (size_t k = 0; k < set.points.size(); ++k) {
    const double dx = p.x - set.points[k].x, dy = p.y - set.points[k].y;
    const double s = dx * dx + dy * dy;
    // Written without OfferCandidate: (s, id) lexicographic, kept sorted.
    auto before = [](double s1, uint64_t i1, double s2, uint64_t i2) {
      return s1 < s2 || (s1 == s2 && i1 < i2);
    };
    if (before(s, set.ids[k], best.squared1, best.id1)) {
      best.squared2 = best.squared1, best.id2 = best.id1, best.point2 = best.point1;
      best.squared1 = s, best.id1 = set.ids[k], best.point1 = set.points[k];
    } else if (before(s, set.ids[k], best.squared2, best.id2)) {
      best.squared2 = s, best.id2 = set.ids[k], best.point2 = set.points[k];
    }
  }
  return best;
}

bool Same(const TwoNearest& a, const TwoNearest& b) {
  return a.id1 == b.id1 && a.id2 == b.id2 && a.squared1 == b.squared1 && a.squared2 == b.squared2;
}

// The basis `truth` gives, field by field, against `found`.
bool SameBasis(const TwoNearest& truth, const NearestPoint& found) {
  return found.id == truth.id1 && found.second_id == truth.id2 &&
         found.position.x == truth.point1.x && found.position.y == truth.point1.y &&
         found.f1 == std::sqrt(truth.squared1) && found.f2 == std::sqrt(truth.squared2) &&
         found.cell_value == CellValue(truth.id1);
}

// AnswerEach over `positions`, entries in reverse order of their slots and
// an odd count (so that the pairs straddle the entries and one is alone),
// against the plain scan: where FindTwoNearest certifies, the batch's
// answer must be the scan's; where it refuses, the batch must refuse the
// same entry and leave its slot alone. Returns the mismatches, reporting
// the first few. `fault` plants one, for the test that the check sees it.
enum class BatchFault { kNone, kCrossedSlots, kUnreportedRefusal, kLastBit };
int CountBatchMismatches(const NearestSearchGrid& grid, const PointSet& set,
                         std::vector<Vec2> positions, BatchFault fault = BatchFault::kNone) {
  if (positions.size() % 2 == 0) positions.pop_back();
  const auto count = static_cast<uint32_t>(positions.size());
  std::vector<IndexedPosition> entries;
  for (uint32_t k = 0; k < count; ++k) entries.push_back({positions[k], count - 1 - k});
  if (fault == BatchFault::kCrossedSlots) std::swap(entries[0].index, entries[1].index);
  NearestPoint untouched;
  untouched.id = 0x5eed, untouched.f1 = -1;
  std::vector<NearestPoint> results(count, untouched);
  std::vector<uint32_t> refused = {99};               // appended to, not replaced
  grid.AnswerEach(entries, results, refused, &grid);  // its own lines as the next grid's: a hint
  if (fault == BatchFault::kUnreportedRefusal && refused.size() > 1) refused.pop_back();
  if (fault == BatchFault::kLastBit) results[0].f2 = std::nextafter(results[0].f2, 10.0);
  int mismatches = 0;
  auto report = [&](const std::string& what) {
    if (++mismatches <= 3) ADD_FAILURE() << what;
  };
  size_t next_refused = 1;
  for (uint32_t k = 0; k < count; ++k) {
    const Vec2 p = positions[k];
    const NearestPoint& found = results[count - 1 - k];
    TwoNearest single;
    if (!grid.FindTwoNearest(p, single)) {
      if (next_refused >= refused.size() || refused[next_refused] != k) {
        report("not refused: entry " + std::to_string(k));
      } else {
        ++next_refused;
      }
      if (found.id != untouched.id || found.f1 != untouched.f1) {
        report("slot of refused entry " + std::to_string(k) + " written");
      }
      continue;
    }
    if (!SameBasis(ScanAll(set, p), found)) report("wrong answer for entry " + std::to_string(k));
  }
  if (refused.size() != next_refused) report("refused entries that were certified");
  return mismatches;
}

// Every test runs the search's first pass in each vector width: two lanes
// (SSE2) and the widest this CPU has (four with AVX2, else two again).
class NearestSearchGridTest : public testing::TestWithParam<NearestSearchGrid::FirstPassWidth> {};

INSTANTIATE_TEST_SUITE_P(EveryWidth, NearestSearchGridTest,
                         testing::Values(NearestSearchGrid::FirstPassWidth::kTwoLanes,
                                         NearestSearchGrid::FirstPassWidth::kWidest),
                         [](const auto& info) {
                           return info.param == NearestSearchGrid::FirstPassWidth::kTwoLanes
                                      ? std::string("TwoLanes")
                                      : std::string("Widest");
                         });

TEST_P(NearestSearchGridTest, RunsTheRequestedWidth) {
  const NearestSearchGrid grid(1.0, {0, 0}, {}, {}, GetParam());
  const bool widest = GetParam() == NearestSearchGrid::FirstPassWidth::kWidest;
  EXPECT_EQ(grid.FirstPassLanes(), widest && NearestSearchGrid::FourLanesAvailable() ? 4 : 2);
}

// An integer lattice (d = 1) over region (0, 0) and its margin, with ids
// shuffled so that "smaller id" is not "first scanned".
PointSet Lattice(uint64_t seed) {
  PointSet set;
  for (int y = -4; y < 20; ++y) {
    for (int x = -4; x < 20; ++x) set.points.push_back({x + 0.0, y + 0.0});
  }
  for (size_t k = 0; k < set.points.size(); ++k) set.ids.push_back(k);
  Rng rng(seed);
  for (size_t k = set.ids.size(); k > 1; --k) std::swap(set.ids[k - 1], set.ids[rng.Below(k)]);
  return set;
}

TEST_P(NearestSearchGridTest, TiesOnALatticeGoToTheSmallerId) {
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    const PointSet set = Lattice(seed);
    const NearestSearchGrid grid(1.0, {0, 0}, set.points, set.ids, GetParam());
    Rng rng(seed);
    int ties = 0;
    std::vector<Vec2> positions;
    for (int k = 0; k < 2000; ++k) {
      // Cell centres (four-way ties), edge midpoints (two-way) and lattice points.
      const double x = static_cast<double>(rng.Below(16)) + 0.5 * static_cast<double>(rng.Below(2));
      const double y = static_cast<double>(rng.Below(16)) + 0.5 * static_cast<double>(rng.Below(2));
      TwoNearest found;
      ASSERT_TRUE(grid.FindTwoNearest({x, y}, found)) << x << ", " << y;
      const TwoNearest truth = ScanAll(set, {x, y});
      EXPECT_TRUE(Same(truth, found)) << "seed " << seed << " at " << x << ", " << y;
      if (found.squared1 == found.squared2) ++ties;
      positions.push_back({x, y});
    }
    EXPECT_GT(ties, 500);
    EXPECT_EQ(CountBatchMismatches(grid, set, positions), 0) << "seed " << seed;
  }
}

TEST_P(NearestSearchGridTest, CertifiedAnswersAreExactOnSparseSubsets) {
  int certified = 0, refused = 0;
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    Rng rng(seed);
    // Random points at density from about 1 per d^2 down to 1 per 25 d^2.
    const double density = 1.0 / (1.0 + static_cast<double>(seed % 5) * 6.0);
    PointSet set;
    const int count = static_cast<int>(24 * 24 * density);
    for (int k = 0; k < count; ++k) {
      set.points.push_back({rng.Uniform(-4, 20), rng.Uniform(-4, 20)});
      set.ids.push_back(rng.NextBits());
    }
    const NearestSearchGrid grid(1.0, {0, 0}, set.points, set.ids, GetParam());
    std::vector<Vec2> positions;
    for (int k = 0; k < 500; ++k) {
      const Vec2 p{rng.Uniform(-3, 19), rng.Uniform(-3, 19)};
      positions.push_back(p);
      TwoNearest found;
      if (!grid.FindTwoNearest(p, found)) {
        ++refused;
        continue;
      }
      ++certified;
      EXPECT_TRUE(Same(ScanAll(set, p), found)) << "seed " << seed << " at " << p.x << ", " << p.y;
    }
    EXPECT_EQ(CountBatchMismatches(grid, set, positions), 0) << "seed " << seed;
  }
  EXPECT_GT(certified, 1000);
  EXPECT_GT(refused, 1000);  // sparse sets often need cells beyond the grid
}

// A region at d = scale, at the origin or (far) the last one before the
// precision limit; At(u, v) is the point u, v d from its low corner.
struct ScaledRegion {
  ScaledRegion(double scale, bool far)
      : scale(scale),
        key(far ? RegionKey{(int64_t{1} << 28) - 1, -(int64_t{1} << 28)} : RegionKey{0, 0}),
        rect(RegionLayout(scale).RegionRect(key)) {}
  Vec2 At(double u, double v) const { return {rect.x0 + u * scale, rect.y0 + v * scale}; }
  double scale;
  RegionKey key;
  Rect rect;
};

// The search's first pass orders points by their squared distance with its
// low 16 bits replaced by an index, reading a fixed number of points per row
// past the row's end. These sets aim at what that could get wrong: distances
// equal or a few ulps apart (three ways, so that the second place is
// contested too), positions exactly on points (squared distance 0), rows of
// many points, and the smallest and largest d near the precision limit.
TEST_P(NearestSearchGridTest, FirstPassIsExactOnNearTiesPointsDenseRowsAndExtremeScales) {
  int certified = 0, ties = 0;
  auto check = [&](const NearestSearchGrid& grid, const PointSet& set, Vec2 p) {
    TwoNearest found;
    if (!grid.FindTwoNearest(p, found)) return;
    ++certified;
    if (found.squared1 == found.squared2) ++ties;
    EXPECT_TRUE(Same(ScanAll(set, p), found)) << p.x << ", " << p.y;
  };
  for (uint64_t seed = 1; seed <= 40; ++seed) {
    Rng rng(seed);
    const double scale = seed % 4 == 0 ? 0x1.0p-256 : seed % 4 == 1 ? 0x1.0p+256 : 1.0;
    const ScaledRegion region(scale, seed % 2 == 0);
    const RegionKey key = region.key;
    auto at = [&](double u, double v) { return region.At(u, v); };
    // Background points, 1 to 7 per d^2, and a centre p with three points at
    // about the same distance r, each a few ulps (0 to 2^12) from the others.
    const double density = 1.0 + static_cast<double>(seed % 7);
    const Vec2 p = at(rng.Uniform(0, 16), rng.Uniform(0, 16));
    const double r = scale * rng.Uniform(0.05, 0.2);
    PointSet set;
    for (int k = 0; k < static_cast<int>(24 * 24 * density); ++k) {
      const Vec2 q = at(rng.Uniform(-4, 20), rng.Uniform(-4, 20));
      if (std::abs(q.x - p.x) > 2 * r || std::abs(q.y - p.y) > 2 * r) set.points.push_back(q);
    }
    for (Vec2 offset : {Vec2{r, 0}, Vec2{0, r}, Vec2{-r, 0}}) {
      Vec2 q{p.x + offset.x, p.y + offset.y};
      for (uint64_t ulps = rng.Below(2) ? 0 : uint64_t{1} << rng.Below(13); ulps > 0; --ulps) {
        q.x = std::nextafter(q.x, q.x + offset.x);
        q.y = std::nextafter(q.y, q.y + offset.y);
      }
      set.points.push_back(q);
    }
    for (size_t k = 0; k < set.points.size(); ++k) set.ids.push_back(rng.NextBits());
    const NearestSearchGrid grid(scale, key, set.points, set.ids, GetParam());
    std::vector<Vec2> positions = {p};
    for (int k = 0; k < 50; ++k) {
      positions.push_back(at(rng.Uniform(0, 16), rng.Uniform(0, 16)));
      positions.push_back(set.points[rng.Below(set.points.size())]);  // on a point
    }
    for (const Vec2& q : positions) check(grid, set, q);
    EXPECT_EQ(CountBatchMismatches(grid, set, positions), 0) << "seed " << seed;
  }
  EXPECT_GT(certified, 3000);
  EXPECT_GT(ties, 5);
}

// AnswerEach ranks a pair of positions by float squared distances in cell
// units, good to about 2^-18 (1 + D) cells^2, and trusts the order only
// where the three smallest are apart by 2^-11 (1 + T) (docs/noise.md,
// "The paired pass"). Three points at nearly the same distance from p, the
// gaps 2^-4 to 2^-30 relative (either side of the float resolution), at
// distances from 0.6 d down to 2^-20 d (where float rounding is largest
// against the distance), at three scales and far from the origin: every
// answer must be the plain scan's. Sets stay under 1,024 points, the most
// the paired pass takes.
TEST_P(NearestSearchGridTest, PairedPassIsExactWhereFloatsCannotTellDistancesApart) {
  int positions_checked = 0;
  for (uint64_t seed = 1; seed <= 60; ++seed) {
    Rng rng(seed);
    const double scale = seed % 3 == 0 ? 0x1.0p-256 : seed % 3 == 1 ? 0x1.0p+256 : 1.0;
    const ScaledRegion region(scale, seed % 2 == 0);
    const RegionKey key = region.key;
    auto at = [&](double u, double v) { return region.At(u, v); };
    const Vec2 p = at(rng.Uniform(0, 16), rng.Uniform(0, 16));
    const double radius =
        scale * std::ldexp(rng.Uniform(0.3, 0.6), -static_cast<int>(rng.Below(21)));
    // Background about 0.8 points per d^2, none within 1.2 d of p.
    PointSet set;
    for (int k = 0; k < 460; ++k) {
      const Vec2 q = at(rng.Uniform(-4, 20), rng.Uniform(-4, 20));
      if (std::hypot(q.x - p.x, q.y - p.y) > 1.2 * scale) set.points.push_back(q);
    }
    double distance = radius;
    for (int k = 0; k < 3; ++k) {
      const double angle = rng.Uniform(0, 6.283185307179586);
      set.points.push_back({p.x + distance * std::cos(angle), p.y + distance * std::sin(angle)});
      distance *= 1 + std::ldexp(1.0, -4 - static_cast<int>(rng.Below(27)));
    }
    for (size_t k = 0; k < set.points.size(); ++k) set.ids.push_back(rng.NextBits());
    const NearestSearchGrid grid(scale, key, set.points, set.ids, GetParam());
    // p in every pair, beside p itself, random positions and points.
    std::vector<Vec2> positions;
    for (int k = 0; k < 40; ++k) {
      positions.push_back(p);
      positions.push_back(k % 2 ? p : at(rng.Uniform(0, 16), rng.Uniform(0, 16)));
      positions.push_back(set.points[rng.Below(set.points.size())]);
    }
    positions_checked += static_cast<int>(positions.size());
    EXPECT_EQ(CountBatchMismatches(grid, set, positions), 0)
        << "seed " << seed << ", radius " << radius / scale << " d";
  }
  EXPECT_GT(positions_checked, 7000);
}

// With fewer than two points within reach, or a position whose cells leave
// the grid, the search must refuse rather than answer.
TEST_P(NearestSearchGridTest, RefusesRatherThanAnswerWhenPointsAreMissing) {
  const PointSet set = Lattice(9);
  const Vec2 p{7.2, 7.7};
  PointSet lonely;  // only the one nearest point
  for (size_t k = 0; k < set.points.size(); ++k) {
    if (SquaredDistance(set.points[k], p) < 0.3) {
      lonely.points.push_back(set.points[k]);
      lonely.ids.push_back(set.ids[k]);
    }
  }
  ASSERT_EQ(lonely.points.size(), 1u);
  TwoNearest found;
  EXPECT_FALSE(NearestSearchGrid(1.0, {0, 0}, lonely.points, lonely.ids, GetParam())
                   .FindTwoNearest(p, found));
  EXPECT_FALSE(NearestSearchGrid(1.0, {0, 0}, {}, {}, GetParam()).FindTwoNearest(p, found));
  // Positions whose 3x3 block leaves the grid are refused too.
  const NearestSearchGrid full(1.0, {0, 0}, set.points, set.ids);
  EXPECT_FALSE(full.FindTwoNearest({-2.5, 5}, found));
  EXPECT_FALSE(full.FindTwoNearest({5, 19.5}, found));
  EXPECT_TRUE(full.FindTwoNearest({-1.5, 17.5}, found));
  // The batch refuses the same positions, among answered ones.
  EXPECT_EQ(CountBatchMismatches(full, set, {{-2.5, 5}, {3, 4.5}, {5, 19.5}, {-1.5, 17.5}, {8, 8}}),
            0);
}

// The batch comparison must notice answers in the wrong slots (a pair's
// two answers crossed), a refusal not reported and a wrong last bit.
TEST_P(NearestSearchGridTest, BatchComparisonCatchesPlantedFaults) {
  const PointSet set = Lattice(4);
  const NearestSearchGrid grid(1.0, {0, 0}, set.points, set.ids, GetParam());
  // The first is refused (its block leaves the grid), the others answered.
  const std::vector<Vec2> positions = {{-2.5, 5}, {3.2, 4.1}, {9.7, 2.2}, {12.4, 15.9}, {7.3, 7.9}};
  EXPECT_EQ(CountBatchMismatches(grid, set, positions), 0);
  for (const BatchFault fault :
       {BatchFault::kCrossedSlots, BatchFault::kUnreportedRefusal, BatchFault::kLastBit}) {
    ::testing::TestPartResultArray failures;
    int mismatches = 0;
    {
      const ::testing::ScopedFakeTestPartResultReporter quiet(
          ::testing::ScopedFakeTestPartResultReporter::INTERCEPT_ONLY_CURRENT_THREAD, &failures);
      mismatches = CountBatchMismatches(grid, set, positions, fault);
    }
    EXPECT_GT(mismatches, 0) << static_cast<int>(fault);
    EXPECT_EQ(failures.size(), mismatches) << static_cast<int>(fault);
  }
}

}  // namespace
}  // namespace scallop
