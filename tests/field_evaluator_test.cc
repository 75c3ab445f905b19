// FieldEvaluator against RadiusField::Evaluate, bit for bit, on walks that stay in a lattice
// cell, cross its lines and jump far (so the cache is hit, missed and replaced), for 1 to 8
// octaves, far and negative coordinates, and rasters; and FloorWithin62Bits against std::floor.
#include "scallop/field/field_evaluator.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "scallop/random/rng.h"
#include "tests/field_test_fields.h"

namespace scallop {
namespace {

// A walk of spots: mostly small steps of a few r_min (a run's candidates and sweep cells), now
// and then a jump anywhere within `extent` of the origin.
Vec2 NextSpot(Rng& rng, Vec2 x, double step, double extent) {
  if (rng.Below(16) == 0) return {rng.Uniform(-extent, extent), rng.Uniform(-extent, extent)};
  return {x.x + rng.Uniform(-step, step), x.y + rng.Uniform(-step, step)};
}

// Counts spots where the evaluator's bits differ from Evaluate's, over `n` spots of the walk.
int64_t Mismatches(const RadiusField& field, uint64_t seed, int n, double step, double extent,
                   bool check_bounds) {
  FieldEvaluator evaluator(field);
  Rng rng(seed);
  Vec2 x{rng.Uniform(-extent, extent), rng.Uniform(-extent, extent)};
  int64_t mismatches = 0;
  for (int k = 0; k < n; ++k) {
    x = NextSpot(rng, x, step, extent);
    const double expected = field.Evaluate(x);
    const double got = evaluator.Evaluate(x);
    if (std::bit_cast<uint64_t>(expected) != std::bit_cast<uint64_t>(got)) ++mismatches;
    if (check_bounds) {
      const Rect cell{x.x, x.y, x.x + step, x.y + 0.5 * step};
      const RadiusInterval want = field.Bounds(cell);
      const RadiusInterval have = evaluator.Bounds(cell);
      if (want.lo != have.lo || want.hi != have.hi) ++mismatches;
    }
  }
  return mismatches;
}

TEST(FieldEvaluatorTest, NoiseBitsEqualEvaluateForEveryOctaveCount) {
  for (int octaves = 1; octaves <= kMaxNoiseOctaves; ++octaves) {
    for (uint64_t seed = 1; seed <= 3; ++seed) {
      const RadiusField field = field_test::NoiseField(seed, 0.5, 8.0, octaves);
      // Steps of 2 r_min stay in the finest octave's cell most of the time; 1e5 jumps leave it.
      EXPECT_EQ(Mismatches(field, seed, 20000, 1.0, 1e5, true), 0)
          << "octaves " << octaves << " seed " << seed;
      // Far out, where lattice indices are large and coordinates coarse.
      EXPECT_EQ(Mismatches(field, seed + 10, 5000, 1.0, 1e12, false), 0)
          << "far, octaves " << octaves << " seed " << seed;
    }
  }
}

TEST(FieldEvaluatorTest, RasterAndConstantDelegate) {
  const Rect area{-50.0, -30.0, 70.0, 60.0};
  const RadiusField raster =
      field_test::RasterField(5, 1.0, 8.0, 12, 9, area.x0, area.y0, area.Width(), true);
  EXPECT_EQ(Mismatches(raster, 5, 5000, 2.0, 100.0, true), 0);
  EXPECT_EQ(Mismatches(RadiusField::Constant(1.5), 6, 1000, 2.0, 100.0, true), 0);
}

// The comparison has power: corners from another lattice (here another seed's) disagree almost
// everywhere, so a cache serving a stale cell's corners is seen (as it was when planted: a cache
// keyed on i alone failed NoiseBitsEqualEvaluateForEveryOctaveCount).
TEST(FieldEvaluatorTest, ComparisonSeesADifferentLattice) {
  const RadiusField a = field_test::NoiseField(1, 0.5, 8.0);
  const RadiusField b = field_test::NoiseField(2, 0.5, 8.0);
  FieldEvaluator evaluator(a);
  Rng rng(3);
  int differ = 0;
  for (int k = 0; k < 1000; ++k) {
    const Vec2 x{rng.Uniform(-1e4, 1e4), rng.Uniform(-1e4, 1e4)};
    differ += evaluator.Evaluate(x) != b.Evaluate(x) ? 1 : 0;
  }
  EXPECT_GT(differ, 990);
}

TEST(FieldEvaluatorTest, FloorWithin62BitsIsFloor) {
  Rng rng(11);
  const double specials[] = {0.0,
                             -0.0,
                             0.5,
                             -0.5,
                             1.0,
                             -1.0,
                             0x1p52,
                             -0x1p52,
                             0x1p52 + 1,
                             -0x1p52 - 1,
                             0x1p62,
                             -0x1p62,
                             0x1p-1074,
                             -0x1p-1074,
                             4503599627370495.5,
                             -4503599627370495.5};
  for (double x : specials) {
    EXPECT_EQ(FloorWithin62Bits(x), std::floor(x)) << x;
  }
  int64_t wrong = 0;
  for (int k = 0; k < 200000; ++k) {
    // Magnitudes from 2^-20 to 2^62, both signs, plus exact integers and halves.
    const double magnitude = std::ldexp(rng.Uniform(), static_cast<int>(rng.Below(83)) - 20);
    double x = rng.Below(2) == 0 ? magnitude : -magnitude;
    if (rng.Below(8) == 0) x = std::round(x);
    if (rng.Below(8) == 0) x = std::round(x) + 0.5;
    wrong += FloorWithin62Bits(x) != std::floor(x) ? 1 : 0;
  }
  EXPECT_EQ(wrong, 0);
}

}  // namespace
}  // namespace scallop
