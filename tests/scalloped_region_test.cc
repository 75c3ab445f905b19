// Tests for ScallopedRegion set operations against a point-membership oracle: random annuli and
// random sequences of disk subtractions / intersections and half-plane clips, then membership,
// area, disjointness and sampling checks; plus the degenerate cases named in the design.
#include "scallop/geometry/scalloped_region.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <numbers>
#include <vector>

#include "scallop/random/rng.h"

namespace scallop {
namespace {

constexpr double kPi = std::numbers::pi;

enum class OperationKind { kSubtractDisk, kIntersectDisk, kHalfPlane };

struct Operation {
  OperationKind kind;
  Vec2 point;     // disk centre, or half-plane unit normal
  double scalar;  // disk radius, or half-plane offset
};

// The brute-force description of the region: the annulus and the operations applied in order.
struct Oracle {
  Vec2 apex;
  double inner;
  double outer;
  std::vector<Operation> operations;

  bool Contains(Vec2 p) const {
    const double r = Length(p - apex);
    if (r < inner || r > outer) return false;
    for (const Operation& operation : operations) {
      switch (operation.kind) {
        case OperationKind::kSubtractDisk:
          if (Length(p - operation.point) <= operation.scalar) return false;
          break;
        case OperationKind::kIntersectDisk:
          if (Length(p - operation.point) > operation.scalar) return false;
          break;
        case OperationKind::kHalfPlane:
          if (Dot(operation.point, p) > operation.scalar) return false;
          break;
      }
    }
    return true;
  }

  // Distance from p to the nearest boundary of any set involved (an upper bound on how far a
  // correct implementation may disagree with the oracle because of rounding).
  double BoundaryDistance(Vec2 p) const {
    const double r = Length(p - apex);
    double nearest = std::min(std::fabs(r - inner), std::fabs(r - outer));
    for (const Operation& operation : operations) {
      if (operation.kind == OperationKind::kHalfPlane) {
        nearest = std::min(nearest, std::fabs(Dot(operation.point, p) - operation.scalar));
      } else {
        nearest = std::min(nearest, std::fabs(Length(p - operation.point) - operation.scalar));
      }
    }
    return nearest;
  }

  void ApplyTo(ScallopedRegion& region) const {
    for (const Operation& operation : operations) {
      switch (operation.kind) {
        case OperationKind::kSubtractDisk:
          region.SubtractDisk(operation.point, operation.scalar);
          break;
        case OperationKind::kIntersectDisk:
          region.IntersectDisk(operation.point, operation.scalar);
          break;
        case OperationKind::kHalfPlane:
          region.IntersectHalfPlane(operation.point, operation.scalar);
          break;
      }
    }
  }
};

// Random annulus and operations, biased towards the degenerate configurations: centres on the
// apex, circles tangent to the annulus, disks through the apex, lines through the apex.
Oracle RandomOracle(Rng& rng) {
  Oracle oracle;
  oracle.apex = {rng.Uniform(-100.0, 100.0), rng.Uniform(-100.0, 100.0)};
  oracle.outer = rng.Uniform(0.5, 4.0);
  oracle.inner = oracle.outer * rng.Uniform(0.1, 0.8);
  const int count = 1 + static_cast<int>(rng.Below(15));
  for (int i = 0; i < count; ++i) {
    const uint64_t choice = rng.Below(20);
    const Vec2 direction = UnitAt(rng.Uniform(-kPi, kPi));
    double radius = oracle.outer * rng.Uniform(0.1, 1.5);
    double distance = oracle.outer * rng.Uniform(0.0, 2.0);
    switch (rng.Below(6)) {
      case 0:
        distance = 0.0;  // concentric
        break;
      case 1:
        distance = oracle.outer + radius;  // externally tangent to the outer circle
        break;
      case 2:
        distance = std::fabs(oracle.outer - radius);  // internally tangent to the outer circle
        break;
      case 3:
        distance = radius;  // circle through the apex
        break;
      case 4:
        distance = oracle.inner + radius;  // tangent to the inner circle
        break;
      default:
        break;
    }
    const Vec2 centre = oracle.apex + distance * direction;
    if (choice < 14) {
      oracle.operations.push_back({OperationKind::kSubtractDisk, centre, radius});
    } else if (choice < 17) {
      radius = oracle.outer * rng.Uniform(0.3, 2.5);
      oracle.operations.push_back({OperationKind::kIntersectDisk, centre, radius});
    } else {
      const double offset = rng.Below(4) == 0 ? 0.0 : oracle.outer * rng.Uniform(-1.2, 1.2);
      oracle.operations.push_back(
          {OperationKind::kHalfPlane, direction, Dot(direction, oracle.apex) + offset});
    }
  }
  return oracle;
}

// Every sector: ordered angles within [-pi, pi], 0 <= near <= far on a scan of its range.
void ExpectSectorsWellFormed(const ScallopedRegion& region, uint64_t seed) {
  for (const ScallopedSector& sector : region.sectors()) {
    ASSERT_LT(sector.angle_begin, sector.angle_end) << "seed " << seed;
    ASSERT_GE(sector.angle_begin, -kPi) << "seed " << seed;
    ASSERT_LE(sector.angle_end, kPi) << "seed " << seed;
    for (int i = 0; i <= 16; ++i) {
      const double angle = sector.angle_begin + (sector.angle_end - sector.angle_begin) * i / 16.0;
      const double g = sector.near.DistanceAt(angle);
      const double h = sector.far.DistanceAt(angle);
      ASSERT_GE(g, -1e-9) << "seed " << seed;
      ASSERT_LE(g, h + 1e-7) << "seed " << seed << " angle " << angle;
    }
  }
}

TEST(ScallopedRegionTest, MatchesMembershipOracle) {
  constexpr int kProbes = 3000;
  int nonempty_cases = 0;
  for (uint64_t seed = 1; seed <= 1500; ++seed) {
    Rng rng(seed);
    const Oracle oracle = RandomOracle(rng);
    ScallopedRegion region = ScallopedRegion::Annulus(oracle.apex, oracle.inner, oracle.outer);
    oracle.ApplyTo(region);
    ExpectSectorsWellFormed(region, seed);
    if (HasFatalFailure()) return;
    const double half = oracle.outer;
    const double box = 4.0 * half * half;
    int inside = 0;
    for (int i = 0; i < kProbes; ++i) {
      const Vec2 p = oracle.apex + Vec2{rng.Uniform(-half, half), rng.Uniform(-half, half)};
      const bool expected = oracle.Contains(p);
      inside += expected;
      if (oracle.BoundaryDistance(p) < 1e-9) continue;
      ASSERT_EQ(region.Contains(p), expected)
          << "seed " << seed << " probe " << i << " at " << p.x << "," << p.y;
      int owners = 0;
      for (const ScallopedSector& sector : region.sectors())
        owners += sector.Contains(p - oracle.apex);
      ASSERT_LE(owners, 1) << "sectors overlap, seed " << seed;
    }
    // The binomial spread under the claimed area (the observed fraction underestimates it when
    // the region is tiny and few probes land inside).
    const double fraction = static_cast<double>(inside) / kProbes;
    const double claimed = std::clamp(region.Area() / box, 1.0 / kProbes, 1.0);
    const double sigma = std::sqrt(claimed * (1.0 - claimed) / kProbes) + 1.0 / kProbes;
    ASSERT_NEAR(region.Area(), fraction * box, 5.0 * sigma * box) << "seed " << seed;
    double sum = 0.0;
    for (const ScallopedSector& sector : region.sectors()) sum += sector.Area();
    ASSERT_NEAR(region.Area(), sum, 1e-12 * box) << "seed " << seed;
    ASSERT_EQ(region.empty(), region.sectors().empty());
    if (region.empty()) {
      ASSERT_EQ(region.Area(), 0.0);
      continue;
    }
    ++nonempty_cases;
    for (int i = 0; i < 100; ++i) {
      const Vec2 p = region.Sample(rng.Uniform(), rng.Uniform(), rng.Uniform());
      ASSERT_TRUE(oracle.Contains(p) || oracle.BoundaryDistance(p) < 1e-9)
          << "sample outside, seed " << seed << " sample " << i;
    }
  }
  EXPECT_GT(nonempty_cases, 500);  // the generator must not make the test vacuous
}

// Planted fault: a region that skipped one operation must be caught by the membership or area
// comparison whenever that operation changed the region noticeably.
TEST(ScallopedRegionTest, OracleComparisonCatchesASkippedOperation) {
  int caught = 0;
  int meaningful = 0;
  for (uint64_t seed = 1; seed <= 200; ++seed) {
    Rng rng(seed);
    const Oracle oracle = RandomOracle(rng);
    ScallopedRegion full = ScallopedRegion::Annulus(oracle.apex, oracle.inner, oracle.outer);
    oracle.ApplyTo(full);
    Oracle sabotaged = oracle;
    sabotaged.operations.pop_back();
    ScallopedRegion faulty = ScallopedRegion::Annulus(oracle.apex, oracle.inner, oracle.outer);
    sabotaged.ApplyTo(faulty);
    if (faulty.Area() - full.Area() < 0.02 * 4.0 * oracle.outer * oracle.outer) continue;
    ++meaningful;
    bool mismatch = false;
    for (int i = 0; i < 3000 && !mismatch; ++i) {
      const Vec2 p = oracle.apex + Vec2{rng.Uniform(-oracle.outer, oracle.outer),
                                        rng.Uniform(-oracle.outer, oracle.outer)};
      mismatch = oracle.BoundaryDistance(p) >= 1e-9 && faulty.Contains(p) != oracle.Contains(p);
    }
    caught += mismatch;
  }
  EXPECT_GT(meaningful, 20);
  EXPECT_EQ(caught, meaningful);
}

// Whether every sector's cached ends equal, bit for bit, a fresh SectorEnds::Of at its cached
// directions (Sample and the operations use the cache instead of recomputing).
bool CachedEndsAreExact(const ScallopedRegion& region) {
  for (size_t i = 0; i < region.sectors().size(); ++i) {
    const SectorEnds& cached = region.sector_ends(i);
    const SectorEnds fresh =
        SectorEnds::Of(region.sectors()[i], cached.begin_direction, cached.end_direction);
    if (std::memcmp(&cached.near_begin, &fresh.near_begin, sizeof(double)) != 0 ||
        std::memcmp(&cached.near_end, &fresh.near_end, sizeof(double)) != 0 ||
        std::memcmp(&cached.far_begin, &fresh.far_begin, sizeof(double)) != 0 ||
        std::memcmp(&cached.far_end, &fresh.far_end, sizeof(double)) != 0) {
      return false;
    }
  }
  return true;
}

TEST(ScallopedRegionTest, CachedSectorEndsMatchRecomputation) {
  int sectors_checked = 0;
  for (uint64_t seed = 1; seed <= 1500; ++seed) {
    Rng rng(seed);
    const Oracle oracle = RandomOracle(rng);
    ScallopedRegion region = ScallopedRegion::Annulus(oracle.apex, oracle.inner, oracle.outer);
    // After every operation, not only the last: each one makes and keeps sectors its own way.
    for (const Operation& operation : oracle.operations) {
      Oracle step = oracle;
      step.operations = {operation};
      step.ApplyTo(region);
      ASSERT_TRUE(CachedEndsAreExact(region)) << "seed " << seed;
      sectors_checked += static_cast<int>(region.sectors().size());
    }
  }
  EXPECT_GT(sectors_checked, 10000);
}

// Planted fault: a sector whose curve moved by a hair after its ends were cached is caught.
TEST(ScallopedRegionTest, CachedEndsCheckCatchesAMovedCurve) {
  ScallopedRegion region = ScallopedRegion::Annulus({3.0, -2.0}, 1.0, 2.0);
  region.SubtractDisk({3.0 + 1.7, -2.0 + 0.4}, 1.0);
  ASSERT_TRUE(CachedEndsAreExact(region));
  int caught = 0;
  int planted = 0;
  for (size_t i = 0; i < region.sectors().size(); ++i) {
    for (const bool far : {false, true}) {
      ScallopedRegion copy = region;
      auto& sector = const_cast<ScallopedSector&>(copy.sectors()[i]);
      RadialCurve& curve = far ? sector.far : sector.near;
      // Circles about the apex have no remainder to get wrong; move the others.
      if (curve.centre() == Vec2{0.0, 0.0}) continue;
      const Vec2 moved = curve.centre() + Vec2{1e-9, -1e-9};
      curve = RadialCurve::Arc(moved, curve.radius(), curve.sign());
      ++planted;
      caught += !CachedEndsAreExact(copy);
    }
  }
  EXPECT_GT(planted, 0);
  EXPECT_EQ(caught, planted);
}

// Whether two regions hold the same sectors, cached ends and area, bit for bit.
bool SameBits(const ScallopedRegion& a, const ScallopedRegion& b) {
  if (a.sectors().size() != b.sectors().size()) return false;
  const double area_a = a.Area(), area_b = b.Area();
  const Vec2 apex_a = a.apex(), apex_b = b.apex();
  if (std::memcmp(&area_a, &area_b, sizeof(double)) != 0 ||
      std::memcmp(&apex_a, &apex_b, sizeof(Vec2)) != 0) {
    return false;
  }
  for (size_t i = 0; i < a.sectors().size(); ++i) {
    const ScallopedSector &sa = a.sectors()[i], &sb = b.sectors()[i];
    const double bounds_a[2] = {sa.angle_begin, sa.angle_end};
    const double bounds_b[2] = {sb.angle_begin, sb.angle_end};
    if (std::memcmp(bounds_a, bounds_b, sizeof(bounds_a)) != 0 || !(sa.near == sb.near) ||
        !(sa.far == sb.far) ||
        std::memcmp(&a.sector_ends(i), &b.sector_ends(i), sizeof(SectorEnds)) != 0) {
      return false;
    }
  }
  return true;
}

// A1 moves one annulus to every new point instead of rebuilding it: the result, and everything
// done to it afterwards, must be what Reset gives.
TEST(ScallopedRegionTest, AssignMovedEqualsReset) {
  for (uint64_t seed = 1; seed <= 300; ++seed) {
    Rng rng(seed);
    const Oracle oracle = RandomOracle(rng);
    const ScallopedRegion shape = ScallopedRegion::Annulus(
        {rng.Uniform(-1e3, 1e3), rng.Uniform(-1e3, 1e3)}, oracle.inner, oracle.outer);
    ScallopedRegion moved = ScallopedRegion::Annulus({5.0, 5.0}, 1.0, 9.0);  // used before
    moved.SubtractDisk({6.0, 5.0}, 3.0);
    moved.AssignMoved(shape, oracle.apex);
    ScallopedRegion reset = ScallopedRegion::Annulus(oracle.apex, oracle.inner, oracle.outer);
    ASSERT_TRUE(SameBits(moved, reset)) << "seed " << seed;
    oracle.ApplyTo(moved);
    oracle.ApplyTo(reset);
    ASSERT_TRUE(SameBits(moved, reset)) << "seed " << seed;
  }
}

// Planted fault: the comparison tells apart an annulus moved to an apex one ulp away.
TEST(ScallopedRegionTest, SameBitsCatchesAnApexOneUlpAway) {
  const ScallopedRegion shape = ScallopedRegion::Annulus({0.0, 0.0}, 1.0, 2.0);
  ScallopedRegion moved;
  moved.AssignMoved(shape, {3.0, std::nextafter(4.0, 5.0)});
  EXPECT_FALSE(SameBits(moved, ScallopedRegion::Annulus({3.0, 4.0}, 1.0, 2.0)));
  moved.AssignMoved(shape, {3.0, 4.0});
  EXPECT_TRUE(SameBits(moved, ScallopedRegion::Annulus({3.0, 4.0}, 1.0, 2.0)));
}

// A more accurate area check on fewer cases: Monte Carlo with many probes.
TEST(ScallopedRegionTest, AreaMatchesMonteCarloClosely) {
  constexpr int kProbes = 200000;
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    Rng rng(4000 + seed);
    const Oracle oracle = RandomOracle(rng);
    ScallopedRegion region = ScallopedRegion::Annulus(oracle.apex, oracle.inner, oracle.outer);
    oracle.ApplyTo(region);
    const double half = oracle.outer;
    const double box = 4.0 * half * half;
    int inside = 0;
    for (int i = 0; i < kProbes; ++i) {
      inside +=
          oracle.Contains(oracle.apex + Vec2{rng.Uniform(-half, half), rng.Uniform(-half, half)});
    }
    // The binomial spread under the claimed area (the observed fraction underestimates it when
    // the region is tiny and few probes land inside).
    const double fraction = static_cast<double>(inside) / kProbes;
    const double claimed = std::clamp(region.Area() / box, 1.0 / kProbes, 1.0);
    const double sigma = std::sqrt(claimed * (1.0 - claimed) / kProbes) + 1.0 / kProbes;
    EXPECT_NEAR(region.Area(), fraction * box, 5.0 * sigma * box) << "seed " << 4000 + seed;
  }
}

// Normalised chi-square excess ((chi2 - dof) / sqrt(2 dof), ~N(0,1) under uniformity) of
// `sampler` over a 10x10 grid on the region's bounding box; cell probabilities from membership on
// a fine grid.
double ChiSquareExcess(const ScallopedRegion& region, const std::function<Vec2(Rng&)>& sampler,
                       Rng& rng) {
  constexpr int kCells = 10;
  constexpr int kFine = 500;
  const double half = region.BoundingRadius();
  const Vec2 low = region.apex() - Vec2{half, half};
  std::vector<double> probability(kCells * kCells, 0.0);
  double inside = 0.0;
  for (int i = 0; i < kFine; ++i) {
    for (int j = 0; j < kFine; ++j) {
      const Vec2 p = low + Vec2{2.0 * half * (i + 0.5) / kFine, 2.0 * half * (j + 0.5) / kFine};
      if (!region.Contains(p)) continue;
      probability[(i * kCells / kFine) * kCells + j * kCells / kFine] += 1.0;
      inside += 1.0;
    }
  }
  constexpr int kSamples = 50000;
  std::vector<double> observed(kCells * kCells, 0.0);
  for (int s = 0; s < kSamples; ++s) {
    const Vec2 p = sampler(rng) - low;
    const int i = std::clamp(static_cast<int>(p.x / (2.0 * half) * kCells), 0, kCells - 1);
    const int j = std::clamp(static_cast<int>(p.y / (2.0 * half) * kCells), 0, kCells - 1);
    observed[i * kCells + j] += 1.0;
  }
  double statistic = 0.0;
  int dof = -1;
  for (int c = 0; c < kCells * kCells; ++c) {
    const double expected = kSamples * probability[c] / inside;
    if (expected < 20.0) continue;
    statistic += (observed[c] - expected) * (observed[c] - expected) / expected;
    ++dof;
  }
  return dof < 1 ? 0.0 : (statistic - dof) / std::sqrt(2.0 * dof);
}

constexpr double kChiSquareThreshold = 6.0;

// An A1-like neighbourhood: annulus (2r, 4r) with nearby disks of radius 4r and 2r removed.
ScallopedRegion NeighbourhoodLikeRegion(Rng& rng) {
  ScallopedRegion region = ScallopedRegion::Annulus({3.0, -2.0}, 2.0, 4.0);
  for (int i = 0; i < 4; ++i) {
    region.SubtractDisk(Vec2{3.0, -2.0} + rng.Uniform(2.0, 6.0) * UnitAt(rng.Uniform(-kPi, kPi)),
                        i < 2 ? 4.0 : 2.0);
  }
  return region;
}

TEST(ScallopedRegionTest, SamplesAreUniformByChiSquare) {
  int tested = 0;
  for (uint64_t seed = 1; seed <= 12; ++seed) {
    Rng rng(7000 + seed);
    const ScallopedRegion region = NeighbourhoodLikeRegion(rng);
    if (region.empty() || region.sectors().size() < 2) continue;
    ++tested;
    const double excess = ChiSquareExcess(
        region, [&](Rng& r) { return region.Sample(r.Uniform(), r.Uniform(), r.Uniform()); }, rng);
    EXPECT_LT(excess, kChiSquareThreshold) << "seed " << 7000 + seed;
  }
  EXPECT_GT(tested, 5);
}

TEST(ScallopedRegionTest, ChiSquareCatchesSectorChosenUniformly) {
  // Planted fault: pick the sector uniformly instead of by area.
  ScallopedRegion region = ScallopedRegion::Annulus({0.0, 0.0}, 2.0, 4.0);
  region.SubtractDisk({4.5, 0.5}, 4.0);
  region.SubtractDisk({-1.0, -5.0}, 2.0);
  region.SubtractDisk({-3.5, 3.0}, 2.0);
  ASSERT_GE(region.sectors().size(), 3u);
  Rng rng(99);
  const double honest = ChiSquareExcess(
      region, [&](Rng& r) { return region.Sample(r.Uniform(), r.Uniform(), r.Uniform()); }, rng);
  const double biased = ChiSquareExcess(
      region,
      [&](Rng& r) {
        const auto& sectors = region.sectors();
        const ScallopedSector& sector = sectors[r.Below(sectors.size())];
        return region.apex() + sector.Sample(r.Uniform(), r.Uniform());
      },
      rng);
  EXPECT_LT(honest, kChiSquareThreshold);
  EXPECT_GT(biased, kChiSquareThreshold);
}

double AnnulusArea(double inner, double outer) { return kPi * (outer * outer - inner * inner); }

// Area of the part of the disk of radius R (centred at the origin) beyond the line x = c.
double SegmentArea(double radius, double c) {
  if (c >= radius) return 0.0;
  if (c <= -radius) return kPi * radius * radius;
  return radius * radius * std::acos(c / radius) - c * std::sqrt(radius * radius - c * c);
}

// Area of the intersection of two disks with radii r1, r2 whose centres are d apart.
double LensArea(double r1, double r2, double d) {
  if (d >= r1 + r2) return 0.0;
  if (d <= std::fabs(r1 - r2)) return kPi * std::min(r1, r2) * std::min(r1, r2);
  return r1 * r1 * std::acos((d * d + r1 * r1 - r2 * r2) / (2.0 * d * r1)) +
         r2 * r2 * std::acos((d * d + r2 * r2 - r1 * r1) / (2.0 * d * r2)) -
         0.5 * std::sqrt((-d + r1 + r2) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2));
}

TEST(ScallopedRegionTest, DegenerateDiskCases) {
  const Vec2 apex{10.0, -3.0};
  const double inner = 1.0;
  const double outer = 2.0;
  const double full = AnnulusArea(inner, outer);
  const auto fresh = [&] { return ScallopedRegion::Annulus(apex, inner, outer); };
  {
    ScallopedRegion region = fresh();
    EXPECT_NEAR(region.Area(), full, 1e-13);
    region.SubtractDisk(apex + Vec2{2.5, 0.0}, 0.5);  // externally tangent: unchanged
    EXPECT_NEAR(region.Area(), full, 1e-13);
    region.SubtractDisk(apex + Vec2{50.0, 0.0}, 3.0);  // misses
    EXPECT_NEAR(region.Area(), full, 1e-13);
    region.SubtractDisk(apex + Vec2{0.2, 0.1}, 0.5);  // inside the hole
    EXPECT_NEAR(region.Area(), full, 1e-13);
  }
  {
    ScallopedRegion region = fresh();
    region.SubtractDisk(apex + Vec2{0.0, 1.7}, 0.3);  // internally tangent to the outer circle
    EXPECT_NEAR(region.Area(), full - kPi * 0.09, 1e-12);
    region.SubtractDisk(apex + Vec2{-1.3, 0.0}, 0.3);  // tangent to the inner circle from outside
    EXPECT_NEAR(region.Area(), full - 2.0 * kPi * 0.09, 1e-12);
    region.SubtractDisk(apex + Vec2{0.0, -1.5}, 0.5);  // tangent to both circles
    EXPECT_NEAR(region.Area(), full - 2.0 * kPi * 0.09 - kPi * 0.25, 1e-12);
  }
  {
    ScallopedRegion region = fresh();
    region.SubtractDisk(apex, 1.5);  // concentric: a thinner annulus
    EXPECT_NEAR(region.Area(), AnnulusArea(1.5, outer), 1e-12);
    EXPECT_TRUE(region.Contains(apex + Vec2{0.0, 1.75}));
    EXPECT_FALSE(region.Contains(apex + Vec2{0.0, 1.25}));
    region.SubtractDisk(apex, 1.5);  // the same disk again: unchanged
    EXPECT_NEAR(region.Area(), AnnulusArea(1.5, outer), 1e-12);
    region.IntersectDisk(apex, 1.8);
    EXPECT_NEAR(region.Area(), AnnulusArea(1.5, 1.8), 1e-12);
    region.IntersectDisk(apex, 1.8);
    EXPECT_NEAR(region.Area(), AnnulusArea(1.5, 1.8), 1e-12);
  }
  {
    ScallopedRegion region = fresh();
    region.SubtractDisk(apex + Vec2{0.5, 0.5}, 3.0);  // contains the whole region
    EXPECT_TRUE(region.empty());
    EXPECT_EQ(region.Area(), 0.0);
    region.SubtractDisk(apex, 1.0);  // operations on the empty region are harmless
    region.IntersectHalfPlane({1.0, 0.0}, 0.0);
    EXPECT_TRUE(region.empty());
    EXPECT_FALSE(region.Contains(apex + Vec2{1.5, 0.0}));
  }
  {
    ScallopedRegion region = fresh();
    region.IntersectDisk(apex + Vec2{0.5, 0.5}, 3.0);  // contains the whole region: unchanged
    EXPECT_NEAR(region.Area(), full, 1e-13);
    region.IntersectDisk(apex + Vec2{10.0, 0.0}, 3.0);  // misses: empty
    EXPECT_TRUE(region.empty());
  }
  {
    // A disk of the outer radius shifted by e: leaves a thin crescent (a sliver) of area
    // pi R^2 - lens(R, R, e).
    for (const double e : {1e-2, 1e-4, 1e-6}) {
      ScallopedRegion region = fresh();
      region.SubtractDisk(apex + Vec2{e, 0.0}, outer);
      const double lens = 2.0 * outer * outer * std::acos(e / (2.0 * outer)) -
                          0.5 * e * std::sqrt(4.0 * outer * outer - e * e);
      EXPECT_NEAR(region.Area(), kPi * outer * outer - lens, 1e-12) << "e " << e;
      EXPECT_FALSE(region.Contains(apex + Vec2{0.0, 1.5}));
      if (e >= 1e-4) {
        EXPECT_TRUE(region.Contains(apex + Vec2{-outer + 0.3 * e, 0.0})) << "e " << e;
      }
    }
  }
  {
    // A disk through the apex, and one containing it (the apex-inside case).
    ScallopedRegion through = fresh();
    through.SubtractDisk(apex + Vec2{0.0, 0.75}, 0.75);
    EXPECT_NEAR(through.Area(), full - (kPi * 0.75 * 0.75 - LensArea(inner, 0.75, 0.75)), 1e-12);
    ScallopedRegion containing = fresh();
    containing.SubtractDisk(apex + Vec2{0.3, 0.0}, 1.5);
    EXPECT_NEAR(containing.Area(), full - (LensArea(outer, 1.5, 0.3) - kPi * inner * inner), 1e-12);
    ScallopedRegion kept = fresh();
    kept.IntersectDisk(apex + Vec2{0.3, 0.0}, 1.5);
    EXPECT_NEAR(kept.Area(), LensArea(outer, 1.5, 0.3) - kPi * inner * inner, 1e-12);
  }
}

// A subtracted disk that holds a whole sector drops it without splitting it (a shortcut taken for
// about half the sectors A1's disks reach). The shortcut must not take a sector that pokes out of
// the disk by a hair: the lower half-annulus 1..2 about the origin lies inside the disk about
// (0, -t) of radius sqrt(4 + t^2) save for two slivers at (+-2, 0), and those slivers must stay.
TEST(ScallopedRegionTest, DiskHoldingAlmostAllOfASectorKeepsItsSlivers) {
  for (const double t : {0.3, 0.5, 1.0}) {
    const Vec2 centre{0.0, -t};
    const double reach = std::sqrt(4.0 + t * t);  // the half-annulus's farthest point from centre
    const Vec2 lower_probe{0.0, -1.5};
    // Points of the lower half-annulus just inside its corners at (+-2, 0).
    const Vec2 slivers[2] = {(2.0 - 1e-7) * Vec2{std::cos(-1e-6), std::sin(-1e-6)},
                             (2.0 - 1e-7) * Vec2{std::cos(-kPi + 1e-6), std::sin(-kPi + 1e-6)}};

    ScallopedRegion held = ScallopedRegion::Annulus({0.0, 0.0}, 1.0, 2.0);
    held.SubtractDisk(centre, reach * (1.0 + 1e-7));
    EXPECT_FALSE(held.Contains(lower_probe)) << t;
    for (const Vec2& p : slivers) EXPECT_FALSE(held.Contains(p)) << t;

    ScallopedRegion poking = ScallopedRegion::Annulus({0.0, 0.0}, 1.0, 2.0);
    poking.SubtractDisk(centre, reach * (1.0 - 1e-5));
    EXPECT_FALSE(poking.Contains(lower_probe)) << t;
    for (const Vec2& p : slivers) {
      ASSERT_GT(Length(p - centre), reach * (1.0 - 1e-5));  // outside the disk, in the annulus
      EXPECT_TRUE(poking.Contains(p)) << t << " " << p.x << " " << p.y;
    }
  }
}

TEST(ScallopedRegionTest, DegenerateHalfPlaneCases) {
  const Vec2 apex{-4.0, 7.0};
  const double inner = 1.0;
  const double outer = 3.0;
  const double full = AnnulusArea(inner, outer);
  const auto fresh = [&] { return ScallopedRegion::Annulus(apex, inner, outer); };
  for (int i = 0; i < 16; ++i) {
    const Vec2 normal = UnitAt(-kPi + i * kPi / 8.0 + 0.01 * i);
    const double base = Dot(normal, apex);
    {
      ScallopedRegion region = fresh();
      region.IntersectHalfPlane(normal, base);  // through the apex: half the annulus
      EXPECT_NEAR(region.Area(), 0.5 * full, 1e-12) << i;
      EXPECT_TRUE(region.Contains(apex - 2.0 * normal));
      EXPECT_FALSE(region.Contains(apex + 2.0 * normal));
    }
    for (const double c : {0.3, 1.0, 1.7, 2.9}) {
      ScallopedRegion keep_apex = fresh();
      keep_apex.IntersectHalfPlane(normal, base + c);  // apex on the kept side
      EXPECT_NEAR(keep_apex.Area(), full - SegmentArea(outer, c) + SegmentArea(inner, c), 1e-12)
          << i << " " << c;
      ScallopedRegion lose_apex = fresh();
      lose_apex.IntersectHalfPlane(-1.0 * normal, -(base + c));  // apex outside the kept side
      EXPECT_NEAR(lose_apex.Area(), SegmentArea(outer, c) - SegmentArea(inner, c), 1e-12)
          << i << " " << c;
    }
    ScallopedRegion region = fresh();
    region.IntersectHalfPlane(normal, base + outer);  // contains the region (tangent)
    EXPECT_NEAR(region.Area(), full, 1e-13);
    region.IntersectHalfPlane(normal, base - outer);  // misses it
    EXPECT_TRUE(region.empty());
  }
  // Clipping to a rectangle around the apex: the square [-1.5, 1.5]^2 minus the unit disk.
  ScallopedRegion region = fresh();
  region.IntersectHalfPlane({1.0, 0.0}, apex.x + 1.5);
  region.IntersectHalfPlane({-1.0, 0.0}, -(apex.x - 1.5));
  region.IntersectHalfPlane({0.0, 1.0}, apex.y + 1.5);
  region.IntersectHalfPlane({0.0, -1.0}, -(apex.y - 1.5));
  EXPECT_NEAR(region.Area(), 9.0 - kPi, 1e-12);
}

}  // namespace
}  // namespace scallop
