// Radius-field worlds on the infinite plane (issue 24), judged on the engine's real output by
// brute force written apart from the code under test: every pair against the max rule, and
// dense probing of G with R at the probe, over windows centred on region seams and corners,
// for a noise field, a raster field and a masked raster; planted faults the world verifier
// must catch; the same points and ids for any tiling, query order, thread count and cache
// size; the id layout.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "scallop/plane/plane_engine.h"
#include "scallop/plane/point_id.h"
#include "scallop/plane/region_layout.h"
#include "scallop/plane/viewport_tracker.h"
#include "scallop/plane/world_verifier.h"
#include "scallop/random/rng.h"
#include "scallop/sampling/field_sampler.h"
#include "scallop/verify/field_verifier.h"
#include "tests/field_test_fields.h"
#include "tests/test_worlds.h"

namespace scallop {
namespace {

using field_test::BruteForceConflicts;
using field_test::BruteForceProbe;
using field_test::FieldCase;

constexpr double kRMin = 1.0;
constexpr double kRatio = 4.0;

// A field world with r_min = 1 (field_test_fields.h).
World FieldWorld(FieldCase c, uint64_t seed, double ratio = kRatio) {
  return field_test::PlaneWorld(c, seed, kRMin, ratio);
}

constexpr FieldCase kCases[] = {FieldCase::kNoise, FieldCase::kRaster, FieldCase::kMaskedRaster};

PlaneEngineOptions EngineOptions(int threads, int64_t cache_bytes) {
  PlaneEngineOptions options;
  options.threads = threads;
  options.cache_bytes = cache_bytes;
  return options;
}

PlanePoints MustPoints(PlaneEngine& engine, const World& world, const Rect& rect) {
  StatusOr<PlanePoints> points = engine.Points(world, rect);
  EXPECT_TRUE(points.ok()) << points.status().message();
  return points.ok() ? *points : PlanePoints{};
}

// A window of about a region a side centred near a random region corner within the raster,
// so that it holds two seams and a corner of four regions.
Rect WindowOnACorner(Rng& rng, const RegionLayout& layout) {
  const double s = layout.side();
  const double cx = s * static_cast<double>(static_cast<int64_t>(rng.Below(3)) - 1);
  const double cy = s * static_cast<double>(static_cast<int64_t>(rng.Below(3)) - 1);
  const double half = 0.5 * s + rng.Uniform(0.0, 0.1 * s);
  const double ox = rng.Uniform(-0.2, 0.2) * s;
  const double oy = rng.Uniform(-0.2, 0.2) * s;
  return {cx + ox - half, cy + oy - half, cx + ox + half, cy + oy + half};
}

// No conflict among the window's points and its halo, every point outside masks, and every
// unmasked spot of the window covered (probed every r_min / 4 with R at the probe); the
// world verifier agrees.
TEST(FieldPlaneTest, NoConflictAndMaximalAcrossSeamsByBruteForce) {
  const struct {
    FieldCase c;
    double ratio;
  } cases[] = {{FieldCase::kNoise, kRatio},
               {FieldCase::kRaster, kRatio},
               {FieldCase::kMaskedRaster, kRatio},
               {FieldCase::kNoise, 16.0},
               {FieldCase::kMaskedRaster, 16.0}};
  for (const auto& [c, ratio] : cases) {
    for (uint64_t seed : {3u, 17u, 40u}) {
      // Ratio 16 windows hold 16 times the points: one seed is enough time.
      if (ratio > kRatio && seed != 3) continue;
      const World world = FieldWorld(c, seed, ratio);
      const RadiusField& field = *world.radius_field();
      const RegionLayout layout(world);
      ASSERT_EQ(layout.side(), 6.0 * ratio * kRMin);
      PlaneEngine engine(EngineOptions(2, int64_t{64} << 20));
      Rng rng(HashWords({seed, static_cast<uint64_t>(c), static_cast<uint64_t>(ratio)}));
      for (int trial = 0; trial < 3; ++trial) {
        const Rect window = WindowOnACorner(rng, layout);
        SCOPED_TRACE(::testing::Message()
                     << field_test::CaseName(c) << " ratio " << ratio << " seed " << seed
                     << " window [" << window.x0 << ", " << window.x1 << ") x [" << window.y0
                     << ", " << window.y1 << ")");
        const PlanePoints halo = MustPoints(engine, world, Grown(window, 2 * field.r_max()));
        ASSERT_GT(halo.positions.size(), 100u);
        EXPECT_EQ(BruteForceConflicts(halo.positions, field), 0);
        int64_t masked = 0;
        for (const Vec2& p : halo.positions) masked += field.IsMasked(p);
        EXPECT_EQ(masked, 0);
        const field_test::ProbeResult probe =
            BruteForceProbe(halo.positions, field, window, 0.25 * kRMin, seed + trial);
        EXPECT_GT(probe.probes, 500);
        EXPECT_LT(probe.worst_gap, 1e-7 * field.r_max())
            << "uncovered spot (" << probe.worst_spot.x << ", " << probe.worst_spot.y << ")";
        StatusOr<VerifyReport> report = VerifyWorldRect(engine, world, window, QueryLimit{});
        ASSERT_TRUE(report.ok()) << report.status().message();
        ASSERT_TRUE(report->field.has_value());
        EXPECT_TRUE(report->passed()) << "conflicts " << report->field->conflicts << ", gap bound "
                                      << report->field->gap_bound;
        // The halo query holds the window's points, ids and all.
        const PlanePoints inside = MustPoints(engine, world, window);
        EXPECT_EQ(report->points_checked, static_cast<int64_t>(inside.positions.size()));
      }
    }
  }
}

// The masked raster really has masks in the windows the test looks at, or the masked case
// tests nothing new.
TEST(FieldPlaneTest, MaskedRasterHasMasksNearTheOrigin) {
  const World world = FieldWorld(FieldCase::kMaskedRaster, 3);
  EXPECT_TRUE(world.radius_field()->AnyMasked({-30, -30, 30, 30}));
  EXPECT_FALSE(world.radius_field()->AllMasked({-30, -30, 30, 30}));
}

// Faults planted in a real window: the verifier must catch each.
TEST(FieldPlaneTest, PlantedFaultsAreCaught) {
  const World world = FieldWorld(FieldCase::kMaskedRaster, 5);
  const RadiusField& field = *world.radius_field();
  PlaneEngine engine(EngineOptions(2, int64_t{64} << 20));
  const Rect window{-14, -10, 18, 20};
  const PlanePoints halo = MustPoints(engine, world, Grown(window, 2 * field.r_max()));
  StatusOr<FieldVerifyReport> clean = VerifyFieldWindow(halo.positions, window, field);
  ASSERT_TRUE(clean.ok()) << clean.status().message();
  ASSERT_TRUE(clean->passed());
  std::vector<size_t> inner;  // points well inside the window
  for (size_t k = 0; k < halo.positions.size(); ++k) {
    if (Grown(window, -field.r_max()).Contains(halo.positions[k])) inner.push_back(k);
  }
  ASSERT_GT(inner.size(), 20u);
  Rng rng(99);
  int removals_judged = 0;
  // 16 trials: a removed point leaves a gap brute force can find in about half of them (3 of
  // the first 8 in version 4's world), and at least 4 must be judged for the test to mean much.
  for (int trial = 0; trial < 16; ++trial) {
    const size_t k = inner[rng.Below(inner.size())];
    // Moved halfway towards its nearest neighbour: a conflict.
    {
      std::vector<Vec2> moved = halo.positions;
      size_t nearest = k == 0 ? 1 : 0;
      for (size_t m = 0; m < moved.size(); ++m) {
        if (m != k &&
            SquaredDistance(moved[m], moved[k]) < SquaredDistance(moved[nearest], moved[k])) {
          nearest = m;
        }
      }
      moved[k] = {0.5 * (moved[k].x + moved[nearest].x), 0.5 * (moved[k].y + moved[nearest].y)};
      StatusOr<FieldVerifyReport> report = VerifyFieldWindow(moved, window, field);
      ASSERT_TRUE(report.ok());
      EXPECT_EQ(report->conflicts, BruteForceConflicts(moved, field));
      EXPECT_GT(report->conflicts, 0);
      EXPECT_FALSE(report->passed());
    }
    // Removed: caught whenever brute force finds the gap it leaves beyond the tolerance.
    {
      std::vector<Vec2> removed = halo.positions;
      const Vec2 spot = removed[k];
      removed.erase(removed.begin() + static_cast<std::ptrdiff_t>(k));
      const field_test::ProbeResult probe =
          BruteForceProbe(removed, field, Grown(Rect{spot.x, spot.y, spot.x, spot.y}, 0.5), 0.05,
                          static_cast<uint64_t>(trial));
      StatusOr<FieldVerifyReport> report = VerifyFieldWindow(removed, window, field);
      ASSERT_TRUE(report.ok());
      if (probe.worst_gap > 1e-8 * field.r_max()) {
        ++removals_judged;
        EXPECT_FALSE(report->maximal_ok) << "removed point (" << spot.x << ", " << spot.y << ")";
      }
      EXPECT_GE(report->gap_bound, probe.worst_gap - 1e-12);
    }
  }
  EXPECT_GE(removals_judged, 4);
  // A point in a mask, inside the window.
  Vec2 in_mask{};
  bool found = false;
  for (double y = window.y0 + 0.5; y < window.y1 && !found; y += 0.5) {
    for (double x = window.x0 + 0.5; x < window.x1 && !found; x += 0.5) {
      if (field.IsMasked({x, y})) in_mask = {x, y}, found = true;
    }
  }
  ASSERT_TRUE(found) << "the window holds no mask";
  std::vector<Vec2> planted = halo.positions;
  planted.push_back(in_mask);
  StatusOr<FieldVerifyReport> report = VerifyFieldWindow(planted, window, field);
  ASSERT_TRUE(report.ok());
  EXPECT_EQ(report->points_masked, 1);
  EXPECT_FALSE(report->passed());
}

// Points with their ids, keyed by id, for comparing answers assembled from different queries.
std::map<uint64_t, Vec2> ById(const PlanePoints& points) {
  std::map<uint64_t, Vec2> by_id;
  for (size_t k = 0; k < points.positions.size(); ++k) {
    EXPECT_TRUE(by_id.emplace(points.ids[k], points.positions[k]).second)
        << "id " << points.ids[k] << " twice";
  }
  return by_id;
}

bool SameBits(const std::map<uint64_t, Vec2>& a, const std::map<uint64_t, Vec2>& b) {
  if (a.size() != b.size()) return false;
  for (auto ia = a.begin(), ib = b.begin(); ia != a.end(); ++ia, ++ib) {
    if (ia->first != ib->first ||
        std::bit_cast<uint64_t>(ia->second.x) != std::bit_cast<uint64_t>(ib->second.x) ||
        std::bit_cast<uint64_t>(ia->second.y) != std::bit_cast<uint64_t>(ib->second.y)) {
      return false;
    }
  }
  return true;
}

// One rectangle asked whole on a fresh one-thread engine, and as random tiles in random order on
// engines with 3 threads, a cache too small for the rectangle, and a history of other queries:
// the same points with the same ids, and every id decodes to the region that holds its point.
TEST(FieldPlaneTest, SamePointsForAnyTilingOrderThreadsAndCache) {
  for (FieldCase c : kCases) {
    const World world = FieldWorld(c, 11);
    const RegionLayout layout(world);
    const Rect rect{-37.5, -29.25, 35.0, 41.5};
    SCOPED_TRACE(field_test::CaseName(c));
    PlaneEngine whole_engine(EngineOptions(1, int64_t{256} << 20));
    const PlanePoints whole = MustPoints(whole_engine, world, rect);
    const std::map<uint64_t, Vec2> expected = ById(whole);
    ASSERT_GT(expected.size(), 500u);
    for (size_t k = 0; k < whole.positions.size(); ++k) {
      const Vec2 p = whole.positions[k];
      const DecodedPointId decoded =
          DecodePointId(whole.ids[k], {0, 0}, layout.point_id_index_bits());
      EXPECT_EQ(decoded.region, layout.RegionOf(p.x, p.y));
    }
    Rng rng(HashWords({0x711e, static_cast<uint64_t>(c)}));
    for (const auto& [threads, cache_bytes] :
         std::vector<std::pair<int, int64_t>>{{3, int64_t{256} << 20}, {2, int64_t{16} << 10}}) {
      PlaneEngine engine(EngineOptions(threads, cache_bytes));
      // History: a query elsewhere first.
      MustPoints(engine, world, {50.0, 60.0, 70.0, 75.0});
      std::vector<double> xs = {rect.x0, rect.x1}, ys = {rect.y0, rect.y1};
      for (int cut = 0; cut < 3; ++cut) {
        xs.push_back(rng.Uniform(rect.x0, rect.x1));
        ys.push_back(rng.Uniform(rect.y0, rect.y1));
      }
      xs.push_back(layout.side());  // a tile edge on a seam
      const std::vector<Rect> tiles = ShuffledTiles(xs, ys, rng);
      PlanePoints assembled;
      for (const Rect& tile : tiles) {
        const PlanePoints part = MustPoints(engine, world, tile);
        assembled.positions.insert(assembled.positions.end(), part.positions.begin(),
                                   part.positions.end());
        assembled.ids.insert(assembled.ids.end(), part.ids.begin(), part.ids.end());
      }
      EXPECT_TRUE(SameBits(ById(assembled), expected))
          << threads << " threads, cache " << cache_bytes << " bytes";
    }
  }
}

// The id layout of field worlds: the index width follows the packing bound of a region, the
// region fields take the rest, and ids round-trip.
TEST(FieldPlaneTest, PointIdLayoutFollowsTheRadiusRatio) {
  EXPECT_EQ(FieldPointIdIndexBits(16.0), 10);       // the constant world's region
  EXPECT_EQ(FieldPointIdIndexBits(6.0 * 8), 12);    // 2,757 points at most
  EXPECT_EQ(FieldPointIdIndexBits(6.0 * 100), 19);  // 416,893 points at most
  EXPECT_EQ(PointIdRegionBits(10), 27);
  EXPECT_EQ(PointIdRegionBits(19), 22);
  Rng rng(4);
  for (int bits : {10, 11, 14, 19}) {
    const int64_t half = int64_t{1} << (PointIdRegionBits(bits) - 1);
    for (int trial = 0; trial < 200; ++trial) {
      const RegionKey key{static_cast<int64_t>(rng.Below(uint64_t{1} << 40)) - (int64_t{1} << 39),
                          static_cast<int64_t>(rng.Below(1000)) - 500};
      const auto index = static_cast<uint32_t>(rng.Below(uint64_t{1} << bits));
      const uint64_t id = EncodePointId(key, index, bits);
      const RegionKey near{key.i + static_cast<int64_t>(rng.Below(2 * half - 2)) - half + 1,
                           key.j - 3};
      const DecodedPointId decoded = DecodePointId(id, near, bits);
      EXPECT_EQ(decoded.region, key) << bits << " bits";
      EXPECT_EQ(decoded.index, index);
    }
  }
  // Constant worlds keep their layout, bit for bit.
  EXPECT_EQ(EncodePointId({1, 2}, 3, 10), EncodePointId({1, 2}, 3));
  EXPECT_EQ(EncodePointId({1, 2}, 3), (uint64_t{1} << 37) | (uint64_t{2} << 10) | 3u);
  // A world's layout: ratio 4 gives 24 r_min regions, 10 bits; ratio 100 gives 19.
  EXPECT_EQ(RegionLayout(FieldWorld(FieldCase::kNoise, 1)).point_id_index_bits(), 10);
  WorldSpec wide{.seed = 1};
  wide.radius_field = field_test::NoiseField(1, 0.5, 100.0).spec();
  const RegionLayout wide_layout(ValidWorld(wide));
  EXPECT_EQ(wide_layout.point_id_index_bits(), 19);
  EXPECT_EQ(wide_layout.side(), 300.0);
  EXPECT_GE(static_cast<double>(wide_layout.regions_per_half_axis()) * wide_layout.side(),
            wide_layout.precision_limit());
}

// Seams in the density: the points' R^2 summed over bands of distance to the nearest seam, per
// unit area (a density normalised by the local spacing), against a bounded SampleField run of
// the same field on the same square. A wall that froze a straight growth front (a sampling
// margin of 0.75 or 1.25 r_max) showed as a band 23% too dense and the next 30% too sparse;
// the margin of 2.25 r_max keeps every band within 4% of the level on average (24 worlds,
// version 4: 0.965 to 1.03). One band of 4 worlds varies by about 0.03 from world to world
// (0.92 to 1.00 for the same band), so 8 worlds are judged against 10%: the worlds vary
// within it, a wall's 23% and 30% do not.
TEST(FieldPlaneTest, DensityIsFlatAcrossSeams) {
  constexpr int kBands = 8;  // of a quarter of the half side, 0.75 r_max
  double plane[kBands] = {}, bounded[kBands] = {};
  PlaneEngine engine(EngineOptions(2, int64_t{256} << 20));
  for (uint64_t s = 0; s < 8; ++s) {
    const World world = FieldWorld(FieldCase::kNoise, 50 + s);
    const RadiusField& field = *world.radius_field();
    const double side = RegionLayout(world).side();
    const Rect square{0, 0, 10 * side, 10 * side};
    const PlanePoints points = MustPoints(engine, world, square);
    StatusOr<std::vector<Vec2>> reference = SampleField({.domain = square, .seed = s}, field);
    ASSERT_TRUE(reference.ok());
    for (int which = 0; which < 2; ++which) {
      for (const Vec2& p : which == 0 ? points.positions : *reference) {
        const double fx = std::fmod(p.x, side), fy = std::fmod(p.y, side);
        const double t = std::min({fx, side - fx, fy, side - fy}) / (side / 2);
        const int band = std::min(kBands - 1, static_cast<int>(t * kBands));
        const double r = field.Evaluate(p);
        (which == 0 ? plane : bounded)[band] += r * r;
      }
    }
  }
  double plane_all = 0.0, bounded_all = 0.0;
  for (int band = 0; band < kBands; ++band) {
    plane_all += plane[band];
    bounded_all += bounded[band];
  }
  // The plane as a whole packs a little looser than one bounded run (its sweeps fill more).
  const double level = plane_all / bounded_all;
  EXPECT_GT(level, 0.95);
  EXPECT_LT(level, 1.02);
  for (int band = 0; band < kBands; ++band) {
    const double ratio = plane[band] / bounded[band] / level;
    std::printf("band %d: plane / bounded %.4f of the level %.4f\n", band, ratio, level);
    EXPECT_GT(ratio, 0.90) << "band " << band;
    EXPECT_LT(ratio, 1.10) << "band " << band;
  }
}

// Follow's tracker on a field world whose regions hold thousands of points (ratio 16: 96 r_min
// regions, and a raster at r_min but for one pixel at r_max): a moving viewport gets each point
// once, and every point in view has been sent.
TEST(FieldPlaneTest, ViewportTrackerSendsEachPointOnce) {
  auto image = std::make_shared<RasterImage>();
  image->width = 3;
  image->height = 3;
  image->pixels = {1, 1, 1, 1, 255, 1, 1, 1, 1};
  WorldSpec spec{.seed = 8};
  spec.radius_field = RadiusFieldSpec{.kind = RadiusFieldKind::kRaster,
                                      .r_min = 1.0,
                                      .r_max = 16.0,
                                      .raster = image,
                                      .raster_origin = {200.0, 200.0},
                                      .pixel_size = 50.0};
  const World world = ValidWorld(spec);
  const RegionLayout layout(world);
  PlaneEngine engine(EngineOptions(2, int64_t{64} << 20));
  ViewportTracker tracker(world);
  std::set<uint64_t> sent;
  uint32_t largest_index = 0;
  for (int step = 0; step < 6; ++step) {
    ViewportUpdate update;
    update.viewport = {-50.0 + 17.0 * step, -20.0 + 5.0 * step, 10.0 + 17.0 * step,
                       30.0 + 5.0 * step};
    update.keep_margin = 500.0;  // nothing is evicted: every point must come once
    ASSERT_TRUE(ValidateViewportUpdate(world, update, 1e8).ok());
    EXPECT_TRUE(tracker.Update(update).empty());
    const PlanePoints in_view = MustPoints(engine, world, update.viewport);
    StatusOr<std::vector<RegionChunk>> chunks = tracker.TakeUnsent(in_view);
    ASSERT_TRUE(chunks.ok()) << chunks.status().message();
    for (const RegionChunk& chunk : *chunks) {
      for (uint64_t id : chunk.points.ids) {
        EXPECT_TRUE(sent.insert(id).second) << "id " << id << " sent twice";
        const DecodedPointId decoded = DecodePointId(id, chunk.key, layout.point_id_index_bits());
        EXPECT_EQ(decoded.region, chunk.key);
        largest_index = std::max(largest_index, decoded.index);
      }
    }
    for (uint64_t id : in_view.ids) EXPECT_TRUE(sent.contains(id));
  }
  EXPECT_GT(largest_index, static_cast<uint32_t>(kMaxPointsPerRegion));
}

}  // namespace
}  // namespace scallop
