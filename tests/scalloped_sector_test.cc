// Tests for RadialCurve and ScallopedSector against brute force: numeric integration of the area,
// Monte Carlo membership, inversion of the cumulative area, and chi-square uniformity of samples
// (with a planted fault the uniformity check must catch).
#include "scallop/geometry/scalloped_sector.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include "scallop/geometry/radial_curve.h"
#include "scallop/random/rng.h"

namespace scallop {
namespace {

constexpr double kPi = std::numbers::pi;

// Whether the ray at `angle` meets `curve` at a positive distance on the branch it names, with a
// margin from tangent rays (where the integrand has a square-root kink that numeric quadrature
// resolves only slowly; the exact tangent case has its own closed-form test).
bool CurveDefinedAt(const RadialCurve& curve, double angle) {
  const Vec2 direction = UnitAt(angle);
  if (!curve.is_arc()) return Dot(curve.normal(), direction) > 0.05;
  const double across = Cross(curve.centre(), direction);
  const double radius_squared = curve.radius() * curve.radius();
  if (radius_squared - across * across < 0.01 * radius_squared) return false;
  return curve.DistanceAlong(direction) >= 0.0;
}

RadialCurve RandomCurve(Rng& rng) {
  const int kind = static_cast<int>(rng.Below(5));
  const Vec2 centre = rng.Uniform(0.0, 3.0) * UnitAt(rng.Uniform(-kPi, kPi));
  switch (kind) {
    case 0:
      return RadialCurve::Arc({0.0, 0.0}, rng.Uniform(0.2, 3.0), +1);
    case 1:
      return RadialCurve::Arc(centre, rng.Uniform(0.2, 3.0), -1);
    case 2:
      return RadialCurve::Arc(centre, rng.Uniform(0.2, 3.0), +1);
    case 3:
      return RadialCurve::Arc(centre, Length(centre) + rng.Uniform(0.2, 2.0), +1);
    default:
      return RadialCurve::Line(UnitAt(rng.Uniform(-kPi, kPi)), rng.Uniform(0.1, 2.0));
  }
}

// A random valid sector (rejection sampling: curves defined, near < far on a dense scan).
ScallopedSector RandomSector(Rng& rng) {
  for (;;) {
    const double begin = rng.Uniform(-kPi, kPi);
    const double end = std::fmin(kPi, begin + rng.Uniform(0.01, kPi));
    if (!(end > begin)) continue;
    ScallopedSector sector{begin, end, RandomCurve(rng), RandomCurve(rng)};
    bool valid = true;
    for (int i = 0; i <= 200 && valid; ++i) {
      const double angle = begin + (end - begin) * i / 200.0;
      valid = CurveDefinedAt(sector.near, angle) && CurveDefinedAt(sector.far, angle) &&
              sector.near.DistanceAt(angle) + 1e-3 < sector.far.DistanceAt(angle);
    }
    if (valid) return sector;
  }
}

double AdaptiveSimpson(const std::function<double(double)>& f, double a, double b, double fa,
                       double fm, double fb, double whole, double tolerance, int depth) {
  const double m = 0.5 * (a + b);
  const double lm = 0.5 * (a + m);
  const double rm = 0.5 * (m + b);
  const double flm = f(lm);
  const double frm = f(rm);
  const double left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
  const double right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
  if (depth <= 0 || std::fabs(left + right - whole) <= 15.0 * tolerance) {
    return left + right + (left + right - whole) / 15.0;
  }
  return AdaptiveSimpson(f, a, m, fa, flm, fm, left, 0.5 * tolerance, depth - 1) +
         AdaptiveSimpson(f, m, b, fm, frm, fb, right, 0.5 * tolerance, depth - 1);
}

double NumericArea(const ScallopedSector& sector, double upto) {
  const auto integrand = [&](double t) {
    const double g = sector.near.DistanceAt(t);
    const double h = sector.far.DistanceAt(t);
    return 0.5 * (h * h - g * g);
  };
  const double a = sector.angle_begin;
  const double fa = integrand(a);
  const double fb = integrand(upto);
  const double fm = integrand(0.5 * (a + upto));
  return AdaptiveSimpson(integrand, a, upto, fa, fm, fb, (upto - a) / 6.0 * (fa + 4.0 * fm + fb),
                         1e-12, 22);
}

// An axis-aligned box containing the sector, found by scanning its far curve.
void BoundingBox(const ScallopedSector& sector, Vec2& low, Vec2& high) {
  low = {0.0, 0.0};
  high = {0.0, 0.0};
  for (int i = 0; i <= 2000; ++i) {
    const double angle = sector.angle_begin + (sector.angle_end - sector.angle_begin) * i / 2000.0;
    for (const RadialCurve* curve : {&sector.near, &sector.far}) {
      const Vec2 p = curve->DistanceAt(angle) * UnitAt(angle);
      low = {std::fmin(low.x, p.x), std::fmin(low.y, p.y)};
      high = {std::fmax(high.x, p.x), std::fmax(high.y, p.y)};
    }
  }
  const double margin = 0.05 * std::fmax(high.x - low.x, high.y - low.y) + 1e-3;
  low = low - Vec2{margin, margin};
  high = high + Vec2{margin, margin};
}

TEST(RadialCurveTest, DistanceMatchesDefinition) {
  Rng rng(11);
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec2 centre = rng.Uniform(0.0, 3.0) * UnitAt(rng.Uniform(-kPi, kPi));
    const double radius = rng.Uniform(0.1, 3.0);
    const RadialCurve far = RadialCurve::Arc(centre, radius, +1);
    const RadialCurve near = RadialCurve::Arc(centre, radius, -1);
    const double angle = rng.Uniform(-kPi, kPi);
    if (!CurveDefinedAt(far, angle)) continue;
    // The point at that distance is on the circle, and the two branches straddle the centre's
    // projection on the ray.
    const Vec2 p = far.DistanceAt(angle) * UnitAt(angle);
    const Vec2 q = near.DistanceAt(angle) * UnitAt(angle);
    EXPECT_NEAR(Length(p - centre), radius, 1e-9) << "trial " << trial;
    EXPECT_NEAR(Length(q - centre), radius, 1e-9) << "trial " << trial;
    EXPECT_LE(near.DistanceAt(angle), far.DistanceAt(angle));
  }
  const RadialCurve line = RadialCurve::Line({0.0, 1.0}, -2.0);  // y = -2, normalised
  EXPECT_EQ(line.normal(), (Vec2{-0.0, -1.0}));
  EXPECT_DOUBLE_EQ(line.offset(), 2.0);
  EXPECT_NEAR(line.DistanceAt(-kPi / 2), 2.0, 1e-15);
  EXPECT_NEAR(line.DistanceAt(-kPi / 4), 2.0 * std::sqrt(2.0), 1e-14);
}

TEST(ScallopedSectorTest, AreaUpToMatchesNumericIntegration) {
  for (uint64_t seed = 1; seed <= 3000; ++seed) {
    Rng rng(seed);
    const ScallopedSector sector = RandomSector(rng);
    const double upto = rng.Uniform(sector.angle_begin, sector.angle_end);
    const double numeric = NumericArea(sector, upto);
    const double scale = std::fmax(1.0, NumericArea(sector, sector.angle_end));
    ASSERT_NEAR(sector.AreaUpTo(upto), numeric, 1e-9 * scale)
        << "seed " << seed << " kinds " << int(sector.near.kind()) << int(sector.far.kind());
    ASSERT_NEAR(sector.Area(), NumericArea(sector, sector.angle_end), 1e-9 * scale)
        << "seed " << seed;
  }
}

TEST(ScallopedSectorTest, FullTangentWedgeOfACircleHasTheDiskArea) {
  // Between the near and far halves of a circle not containing the apex, over the whole wedge of
  // rays that meet it, the sector is the disk: its area is pi R^2 exactly, including the square
  // root's kink at the tangent rays that numeric quadrature handles badly.
  for (uint64_t seed = 1; seed <= 2000; ++seed) {
    Rng rng(700 + seed);
    const double radius = rng.Uniform(0.01, 2.0);
    const double distance = radius * rng.Uniform(1.0001, 20.0);
    const double gamma = rng.Uniform(-2.0, 2.0);
    const double half_width = std::asin(radius / distance);
    if (gamma - half_width < -kPi || gamma + half_width > kPi) continue;
    const Vec2 centre = distance * UnitAt(gamma);
    const ScallopedSector sector{gamma - half_width, gamma + half_width,
                                 RadialCurve::Arc(centre, radius, -1),
                                 RadialCurve::Arc(centre, radius, +1)};
    ASSERT_NEAR(sector.Area(), kPi * radius * radius, 1e-12 * distance * distance)
        << "seed " << 700 + seed;
    // The half up to the centre's direction is exactly half the disk.
    ASSERT_NEAR(sector.AreaUpTo(gamma), 0.5 * kPi * radius * radius, 1e-12 * distance * distance)
        << "seed " << 700 + seed;
    ASSERT_NEAR(sector.AngleAtArea(0.5 * sector.Area()), gamma, 1e-9) << "seed " << 700 + seed;
  }
  // A line and a concentric circle: the circular segment beyond x = c inside radius R.
  const double c = 0.6;
  const double radius = 1.0;
  const double half_width = std::acos(c / radius);
  const ScallopedSector segment{-half_width, half_width, RadialCurve::Line({1.0, 0.0}, c),
                                RadialCurve::Arc({0.0, 0.0}, radius, +1)};
  const double expected = radius * radius * half_width - c * std::sqrt(radius * radius - c * c);
  EXPECT_NEAR(segment.Area(), expected, 1e-14);
}

TEST(ScallopedSectorTest, AreaMatchesMonteCarloMembership) {
  for (uint64_t seed = 1; seed <= 60; ++seed) {
    Rng rng(1000 + seed);
    const ScallopedSector sector = RandomSector(rng);
    Vec2 low, high;
    BoundingBox(sector, low, high);
    const double box = (high.x - low.x) * (high.y - low.y);
    constexpr int kPoints = 40000;
    int inside = 0;
    for (int i = 0; i < kPoints; ++i) {
      const Vec2 p{rng.Uniform(low.x, high.x), rng.Uniform(low.y, high.y)};
      inside += sector.Contains(p);
    }
    const double fraction = static_cast<double>(inside) / kPoints;
    const double sigma = std::sqrt(fraction * (1.0 - fraction) / kPoints) * box;
    EXPECT_NEAR(sector.Area(), fraction * box, 5.0 * sigma + 1e-12) << "seed " << 1000 + seed;
  }
}

TEST(ScallopedSectorTest, AngleAtAreaInvertsAreaUpToAndIsMonotone) {
  for (uint64_t seed = 1; seed <= 3000; ++seed) {
    Rng rng(5000 + seed);
    const ScallopedSector sector = RandomSector(rng);
    const double width = sector.angle_end - sector.angle_begin;
    const double angle = rng.Uniform(sector.angle_begin, sector.angle_end);
    const double recovered = sector.AngleAtArea(sector.AreaUpTo(angle));
    ASSERT_NEAR(recovered, angle, 1e-12 * std::fmax(1.0, std::fabs(angle)))
        << "seed " << 5000 + seed << " width " << width;
    double previous = sector.angle_begin;
    const double area = sector.Area();
    for (int i = 0; i <= 50; ++i) {
      const double next = sector.AngleAtArea(area * i / 50.0);
      ASSERT_GE(next, previous) << "seed " << 5000 + seed << " step " << i;
      previous = next;
    }
    EXPECT_EQ(sector.AngleAtArea(0.0), sector.angle_begin);
    EXPECT_EQ(sector.AngleAtArea(area), sector.angle_end);
  }
}

TEST(ScallopedSectorTest, SamplesLieInsideTheSector) {
  for (uint64_t seed = 1; seed <= 500; ++seed) {
    Rng rng(9000 + seed);
    const ScallopedSector sector = RandomSector(rng);
    for (int i = 0; i < 50; ++i) {
      const Vec2 p = sector.Sample(rng.Uniform(), rng.Uniform());
      const double angle = std::atan2(p.y, p.x);
      const double distance = Length(p);
      ASSERT_GE(angle, sector.angle_begin - 1e-9) << "seed " << 9000 + seed;
      ASSERT_LE(angle, sector.angle_end + 1e-9) << "seed " << 9000 + seed;
      ASSERT_GE(distance, sector.near.DistanceAt(angle) - 1e-9) << "seed " << 9000 + seed;
      ASSERT_LE(distance, sector.far.DistanceAt(angle) + 1e-9) << "seed " << 9000 + seed;
    }
  }
}

// Chi-square of `sampler`'s points over an 8x8 grid on the sector's bounding box, with cell
// probabilities estimated from a fine membership grid. Returns (chi2 - dof) / sqrt(2 dof), about
// N(0, 1) under uniformity; kChiSquareThreshold standard deviations reject.
double ChiSquareExcess(const ScallopedSector& sector,
                       const std::function<Vec2(double, double)>& sampler, Rng& rng) {
  Vec2 low, high;
  BoundingBox(sector, low, high);
  constexpr int kCells = 8;
  constexpr int kFine = 400;
  std::vector<double> probability(kCells * kCells, 0.0);
  double inside = 0.0;
  for (int i = 0; i < kFine; ++i) {
    for (int j = 0; j < kFine; ++j) {
      const Vec2 p{low.x + (high.x - low.x) * (i + 0.5) / kFine,
                   low.y + (high.y - low.y) * (j + 0.5) / kFine};
      if (!sector.Contains(p)) continue;
      probability[(i * kCells / kFine) * kCells + j * kCells / kFine] += 1.0;
      inside += 1.0;
    }
  }
  constexpr int kSamples = 40000;
  std::vector<double> observed(kCells * kCells, 0.0);
  for (int s = 0; s < kSamples; ++s) {
    const Vec2 p = sampler(rng.Uniform(), rng.Uniform());
    int i = static_cast<int>((p.x - low.x) / (high.x - low.x) * kCells);
    int j = static_cast<int>((p.y - low.y) / (high.y - low.y) * kCells);
    i = std::min(std::max(i, 0), kCells - 1);
    j = std::min(std::max(j, 0), kCells - 1);
    observed[i * kCells + j] += 1.0;
  }
  double statistic = 0.0;
  int dof = -1;
  for (int c = 0; c < kCells * kCells; ++c) {
    const double expected = kSamples * probability[c] / inside;
    if (expected < 20.0) continue;  // boundary cells whose area the fine grid estimates poorly
    statistic += (observed[c] - expected) * (observed[c] - expected) / expected;
    ++dof;
  }
  if (dof < 1) return 0.0;
  // Normalised: (chi2 - dof) / sqrt(2 dof) is ~N(0, 1) under uniformity.
  return (statistic - dof) / std::sqrt(2.0 * dof);
}

// The sampler with a planted bias: theta uniform in angle instead of by area.
Vec2 UniformAngleSample(const ScallopedSector& sector, double u1, double u2) {
  const double angle = sector.angle_begin + u2 * (sector.angle_end - sector.angle_begin);
  const double g = sector.near.DistanceAt(angle);
  const double h = sector.far.DistanceAt(angle);
  return std::sqrt(g * g + u1 * (h * h - g * g)) * UnitAt(angle);
}

constexpr double kChiSquareThreshold = 6.0;  // standard deviations of the chi-square statistic

TEST(ScallopedSectorTest, SamplesAreUniformByChiSquare) {
  for (uint64_t seed = 1; seed <= 25; ++seed) {
    Rng rng(20000 + seed);
    const ScallopedSector sector = RandomSector(rng);
    const double excess = ChiSquareExcess(
        sector, [&](double u1, double u2) { return sector.Sample(u1, u2); }, rng);
    EXPECT_LT(excess, kChiSquareThreshold) << "seed " << 20000 + seed;
  }
}

TEST(ScallopedSectorTest, ChiSquareCatchesPlantedAngularBias) {
  // A sector whose width varies strongly with angle: between a near line and an off-apex far arc.
  const ScallopedSector sector{-0.6, 0.9, RadialCurve::Line({1.0, 0.0}, 0.3),
                               RadialCurve::Arc({1.0, 0.5}, 1.2, +1)};
  Rng rng(31337);
  const double honest = ChiSquareExcess(
      sector, [&](double u1, double u2) { return sector.Sample(u1, u2); }, rng);
  const double biased = ChiSquareExcess(
      sector, [&](double u1, double u2) { return UniformAngleSample(sector, u1, u2); }, rng);
  EXPECT_LT(honest, kChiSquareThreshold);
  EXPECT_GT(biased, kChiSquareThreshold);
  // The radial fault (distance uniform instead of by area) must be caught as well.
  const double radial = ChiSquareExcess(
      sector,
      [&](double u1, double u2) {
        const double angle = sector.AngleAtArea(u2 * sector.Area());
        const double g = sector.near.DistanceAt(angle);
        const double h = sector.far.DistanceAt(angle);
        return (g + u1 * (h - g)) * UnitAt(angle);
      },
      rng);
  EXPECT_GT(radial, kChiSquareThreshold);
}

}  // namespace
}  // namespace scallop
