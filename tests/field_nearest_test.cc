// NearestLookup on radius-field worlds (issue 24), against a brute-force oracle written apart
// from the lookup (every engine point of a square about the position, sorted, the square
// doubled until the second nearest lies well inside it): random positions, positions on
// region seams and corners and on points, for noise (ratios 4 and 16), raster and masked
// raster worlds; the bounds maximality gives (F1 < min(r_max, R(p) / (1 - L)),
// F1 + F2 < 2 r_max away from masks); the same bits in any order, with no cache and on two
// threads; a position deep inside a mask refused by name; a planted fault (a grid missing
// its neighbours' points) caught by the comparison.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <tuple>
#include <vector>

#include "scallop/noise/field_nearest_grid.h"
#include "scallop/noise/nearest_lookup.h"
#include "scallop/noise/noise_grid.h"
#include "scallop/plane/plane_engine.h"
#include "scallop/plane/region_layout.h"
#include "scallop/random/rng.h"
#include "tests/field_test_fields.h"
#include "tests/nearest_oracle.h"

namespace scallop {
namespace {

using field_test::FieldCase;
using testing::SameNearest;

// The two nearest by (dx*dx + dy*dy, id), from every point of squares of growing half side
// about p; the answer stands once the second distance is below the half side less a
// margin far above any rounding. Fails the test (and returns nullopt) past 40 r_max.
std::optional<NearestPoint> Oracle(PlaneEngine& engine, const World& world, Vec2 p) {
  const double limit = RegionLayout(world).precision_limit();
  for (double half = 3 * world.max_spacing(); half <= 40 * world.max_spacing(); half *= 2) {
    const Rect square{std::max(p.x - half, -limit), std::max(p.y - half, -limit),
                      std::min(p.x + half, limit), std::min(p.y + half, limit)};
    StatusOr<PlanePoints> points = engine.Points(world, square);
    EXPECT_TRUE(points.ok()) << points.status().message();
    if (!points.ok()) return std::nullopt;
    const std::vector<std::tuple<double, uint64_t, Vec2>> all = testing::SortedByKey(p, *points);
    if (all.size() < 2 || std::sqrt(std::get<0>(all[1])) >= half - 1e-6 * world.min_distance()) {
      continue;
    }
    return NearestPoint{.id = std::get<1>(all[0]),
                        .position = std::get<2>(all[0]),
                        .f1 = std::sqrt(std::get<0>(all[0])),
                        .f2 = std::sqrt(std::get<0>(all[1])),
                        .second_id = std::get<1>(all[1]),
                        .cell_value = CellValue(std::get<1>(all[0]))};
  }
  ADD_FAILURE() << "oracle: no two points within 40 r_max of (" << p.x << ", " << p.y << ")";
  return std::nullopt;
}

// Positions of a test: random ones over the 3 x 3 regions about the origin, and every seam
// and corner among them exactly and one ulp either side.
std::vector<Vec2> TestPositions(const World& world, uint64_t seed, int random_count) {
  const double s = RegionLayout(world).side();
  Rng rng(seed);
  std::vector<Vec2> positions;
  for (int k = 0; k < random_count; ++k) {
    positions.push_back({rng.Uniform(-1.5 * s, 1.5 * s), rng.Uniform(-1.5 * s, 1.5 * s)});
  }
  for (const double seam : {-s, 0.0, s}) {
    for (const double x : {std::nextafter(seam, -INFINITY), seam, std::nextafter(seam, INFINITY)}) {
      positions.push_back({x, rng.Uniform(-1.5 * s, 1.5 * s)});
      positions.push_back({rng.Uniform(-1.5 * s, 1.5 * s), x});
      positions.push_back({x, x});  // a corner of four regions
      positions.push_back({x, -x});
    }
  }
  return positions;
}

// True when no masked spot lies within `radius` of p (a sufficient test: the square about
// the disk is free of masks).
bool FarFromMasks(const World& world, Vec2 p, double radius) {
  const RadiusField& field = *world.radius_field();
  return !field.HasMask() ||
         !field.AnyMasked({p.x - radius, p.y - radius, p.x + radius, p.y + radius});
}

struct WorldCase {
  FieldCase kind;
  double ratio;
};

const WorldCase kWorldCases[] = {{FieldCase::kNoise, 4.0},
                                 {FieldCase::kNoise, 16.0},
                                 {FieldCase::kRaster, 4.0},
                                 {FieldCase::kMaskedRaster, 4.0}};

// Every answer equals the oracle's to the bit, seams and corners included; no fallback away
// from masks; the bounds hold wherever no mask is within r_max.
TEST(FieldNearestTest, MatchesBruteForceAcrossSeamsAndCorners) {
  for (const WorldCase& c : kWorldCases) {
    for (uint64_t seed = 1; seed <= 2; ++seed) {
      SCOPED_TRACE(std::string(field_test::CaseName(c.kind)) + " ratio " + std::to_string(c.ratio) +
                   " seed " + std::to_string(seed));
      const World world = field_test::PlaneWorld(c.kind, seed, 0.75, c.ratio);
      const RadiusField& field = *world.radius_field();
      const double r_max = field.r_max();
      PlaneEngine engine({});
      NearestLookup lookup(engine);
      std::vector<Vec2> positions = TestPositions(world, seed, 150);
      // Positions on points (F1 = 0): the first few points of the window.
      StatusOr<PlanePoints> some = engine.Points(world, {-r_max, -r_max, r_max, r_max});
      ASSERT_TRUE(some.ok());
      for (size_t k = 0; k < some->positions.size() && k < 5; ++k) {
        positions.push_back(some->positions[k]);
      }
      std::vector<NearestPoint> results(positions.size());
      ASSERT_TRUE(lookup.Nearest(world, positions, results).ok());
      double worst_f1 = 0, worst_sum = 0, worst_local = 0;
      int mask_free = 0;
      for (size_t k = 0; k < positions.size(); ++k) {
        const Vec2 p = positions[k];
        const std::optional<NearestPoint> expected = Oracle(engine, world, p);
        ASSERT_TRUE(expected.has_value());
        EXPECT_TRUE(SameNearest(*expected, results[k])) << "at (" << p.x << ", " << p.y << ")";
        if (!FarFromMasks(world, p, r_max)) continue;
        ++mask_free;
        // Maximality's bounds, up to the sampler's tolerance (2.2e-9 r_min).
        const double tolerance = 1e-8 * r_max;
        EXPECT_LT(results[k].f1, r_max + tolerance);
        EXPECT_LT(results[k].f1 + results[k].f2, 2 * r_max + tolerance);
        const double local = field.Evaluate(p) / (1 - field.Slope());
        EXPECT_LT(results[k].f1, local + tolerance);
        worst_f1 = std::max(worst_f1, results[k].f1 / r_max);
        worst_sum = std::max(worst_sum, (results[k].f1 + results[k].f2) / r_max);
        worst_local = std::max(worst_local, results[k].f1 / local);
      }
      EXPECT_GT(mask_free, static_cast<int>(positions.size()) / 2);
      if (c.kind != FieldCase::kMaskedRaster) {
        EXPECT_EQ(lookup.Stats().fallbacks, 0) << "away from masks a grid always certifies";
      }
      std::printf(
          "%s ratio %g seed %d: %zu positions, worst F1 %.3f r_max, F1 + F2 %.3f r_max, "
          "F1 %.3f R(p) / (1 - L); fallbacks %lld\n",
          field_test::CaseName(c.kind), c.ratio, static_cast<int>(seed), positions.size(), worst_f1,
          worst_sum, worst_local, static_cast<long long>(lookup.Stats().fallbacks));
    }
  }
}

// The answer does not depend on the order, the batching, the cache or the threads: reversed
// and one at a time through a lookup that keeps no grid give the same bits; so do the
// brute-force method and two threads sharing a fresh lookup, each half the batch (scallopd's
// calls share one; label "threads", so ThreadSanitizer watches the field grids' building).
TEST(FieldNearestTest, SameBitsWhateverTheOrderBatchingCacheOrThreads) {
  const World world = field_test::PlaneWorld(FieldCase::kMaskedRaster, 7, 1.0, 4.0);
  PlaneEngine engine({});
  NearestLookup cached(engine);
  NearestLookup uncached(engine, {.cache_bytes = 0});
  NearestLookup brute(engine, {.method = NearestMethod::kBruteForce});
  const std::vector<Vec2> positions = TestPositions(world, 7, 300);
  std::vector<NearestPoint> all(positions.size());
  ASSERT_TRUE(cached.Nearest(world, positions, all).ok());
  std::vector<NearestPoint> by_brute_force(positions.size());
  ASSERT_TRUE(brute.Nearest(world, positions, by_brute_force).ok());
  for (size_t n = positions.size(); n-- > 0;) {
    NearestPoint one[1];
    ASSERT_TRUE(uncached.Nearest(world, std::span(&positions[n], 1), one).ok());
    EXPECT_TRUE(SameNearest(all[n], one[0])) << n;
    EXPECT_TRUE(SameNearest(all[n], by_brute_force[n])) << n;
  }

  PlaneEngine two_threads({.threads = 2});
  NearestLookup shared(two_threads);
  const std::vector<NearestPoint> halves = testing::NearestOnTwoThreads(shared, world, positions);
  for (size_t k = 0; k < positions.size(); ++k) EXPECT_TRUE(SameNearest(all[k], halves[k])) << k;
}

// A noise image of a field world equals the lookup at the documented sample positions.
TEST(FieldNearestTest, NoiseGridEqualsTheLookup) {
  const World world = field_test::PlaneWorld(FieldCase::kNoise, 3, 1.0, 8.0);
  PlaneEngine engine({});
  NearestLookup lookup(engine);
  const NoiseGridSpec spec{.origin = {-30.5, -20.25},
                           .step = 0.75,
                           .width = 90,
                           .height = 70,
                           .channel = NoiseChannel::kF2};
  StatusOr<NoiseImage> image = EvaluateNoiseGrid(lookup, world, spec, 1 << 20);
  ASSERT_TRUE(image.ok()) << image.status().message();
  for (int r = 0; r < spec.height; r += 7) {
    for (int c = 0; c < spec.width; c += 5) {
      const Vec2 p{NoiseSampleCoordinate(spec.origin.x, c, spec.step),
                   NoiseSampleCoordinate(spec.origin.y, r, spec.step)};
      const std::optional<NearestPoint> expected = Oracle(engine, world, p);
      ASSERT_TRUE(expected.has_value());
      EXPECT_TRUE(
          testing::SameBits(image->values[static_cast<size_t>(r) * spec.width + c], expected->f2));
    }
  }
  // Regions are counted in the world's own (6 r_max = 48) regions: x from -30.5 to 36.25 and
  // y from -20.25 to 31.5 cross 2 x 2 of them (16 d regions would be 5 x 4).
  EXPECT_EQ(NoiseGridRegions(world, spec), 4);
}

// A raster whose middle 12 x 12 pixels are masked, 8 r_max a pixel: a hole 96 r_max wide.
// Positions in it within 32 r_max of two points are answered exactly (by the fallback);
// its centre, 48 r_max from any point, is OUT_OF_RANGE naming the position.
TEST(FieldNearestTest, PositionsDeepInAMask) {
  auto image = std::make_shared<RasterImage>();
  image->width = image->height = 16;
  image->bit_depth = 8;
  for (int j = 0; j < 16; ++j) {
    for (int i = 0; i < 16; ++i) {
      const bool hole = i >= 2 && i < 14 && j >= 2 && j < 14;
      image->pixels.push_back(hole ? 0 : 255);  // a mask counts as v_max: the slope is 0
    }
  }
  const double r_max = 2.0;
  WorldSpec spec{.seed = 5, .algorithm = WorldAlgorithm::kA3};
  spec.radius_field = RadiusFieldSpec{.kind = RadiusFieldKind::kRaster,
                                      .r_min = 0.5,
                                      .r_max = r_max,
                                      .raster = image,
                                      .raster_origin = {-64 * r_max, -64 * r_max},
                                      .pixel_size = 8 * r_max};
  const World world = ValidWorld(spec);
  PlaneEngine engine({});
  NearestLookup lookup(engine);
  // 10 r_max and 20 r_max inside the hole's edge (at -48 r_max).
  const std::vector<Vec2> inside{{-38 * r_max, 3.25}, {1.5, -28 * r_max}};
  std::vector<NearestPoint> results(inside.size());
  ASSERT_TRUE(lookup.Nearest(world, inside, results).ok());
  for (size_t k = 0; k < inside.size(); ++k) {
    const std::optional<NearestPoint> expected = Oracle(engine, world, inside[k]);
    ASSERT_TRUE(expected.has_value());
    EXPECT_TRUE(SameNearest(*expected, results[k])) << k;
    EXPECT_GT(results[k].f1, 9 * r_max) << k;
  }
  EXPECT_EQ(lookup.Stats().fallbacks, 2);
  const std::vector<Vec2> centre{{0.0, 0.0}, {0.25, 0.5}};
  std::vector<NearestPoint> refused(centre.size());
  const Status status = lookup.Nearest(world, centre, refused);
  EXPECT_EQ(status.code(), StatusCode::kOutOfRange);
  EXPECT_TRUE(status.message().starts_with("positions[0]: fewer than two points within 32 r_max"))
      << status.message();
}

// The comparison catches a grid that lacks its neighbours' points (it certifies answers it
// cannot see past): at least one answer differs from the oracle near the region's edge.
TEST(FieldNearestTest, ComparisonCatchesAGridWithoutItsNeighboursPoints) {
  const World world = field_test::PlaneWorld(FieldCase::kNoise, 9, 1.0, 4.0);
  const RegionLayout layout(world);
  const RadiusField& field = *world.radius_field();
  PlaneEngine engine({});
  const RegionKey key{0, 0};
  StatusOr<PlanePoints> own = engine.Points(world, layout.RegionRect(key));
  ASSERT_TRUE(own.ok());
  const FieldNearestGrid faulty(layout, key, field.r_min(), field.r_max(), own->positions,
                                own->ids);
  Rng rng(9);
  const Rect region = layout.RegionRect(key);
  int wrong = 0, certified = 0;
  for (int k = 0; k < 400; ++k) {
    // Within r_max of the region's edge, where the neighbours' points matter.
    const double t = rng.Uniform(region.x0, region.x1);
    const double inward = rng.Uniform(0.0, field.r_max());
    const Vec2 p = k % 2 == 0 ? Vec2{region.x0 + inward, t} : Vec2{t, region.y1 - inward};
    TwoNearest best;
    if (!faulty.FindTwoNearest(p, best)) continue;
    ++certified;
    const std::optional<NearestPoint> expected = Oracle(engine, world, p);
    ASSERT_TRUE(expected.has_value());
    if (best.id1 != expected->id || best.id2 != expected->second_id) ++wrong;
  }
  EXPECT_GT(certified, 0);
  EXPECT_GT(wrong, 0) << "a grid without its neighbours' points must give wrong answers";
}

}  // namespace
}  // namespace scallop
