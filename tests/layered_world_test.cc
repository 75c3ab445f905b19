// Layered worlds (issue 19) on the infinite plane, judged on the engine's real output by brute
// force written apart from the code under test: every pair under the exclusion matrix, and each
// layer's maximality given the others probed on a lattice, over windows on the seams and corners
// of every layer's regions; planted faults the verifier must catch (a bush moved onto a trunk, a
// rock removed); the same points, ids and layers for any tiling, query order, thread count and
// cache size; a one-layer world equal to the plain world; bad specs named.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "scallop/plane/plane_engine.h"
#include "scallop/plane/region_layout.h"
#include "scallop/plane/world_layers.h"
#include "scallop/plane/world_verifier.h"
#include "scallop/random/rng.h"
#include "tests/field_test_fields.h"
#include "tests/layer_checks.h"
#include "tests/test_worlds.h"

namespace scallop {
namespace {

PlaneEngineOptions EngineOptions(int threads, int64_t cache_bytes) {
  PlaneEngineOptions options;
  options.threads = threads;
  options.cache_bytes = cache_bytes;
  return options;
}

PlanePoints MustPoints(PlaneEngine& engine, const World& world, const Rect& rect,
                       LayerMask layers = kAllLayers) {
  StatusOr<PlanePoints> points = engine.Points(world, rect, layers);
  EXPECT_TRUE(points.ok()) << points.status().message();
  return points.ok() ? *points : PlanePoints{};
}

TEST(LayeredWorldTest, DefaultMatrixIsWeisRule) {
  const World world = Forest(1);
  const WorldLayers& layers = *world.layers();
  ASSERT_EQ(layers.count(), 3);
  EXPECT_EQ(layers.generation_order(), (std::vector<int>{0, 1, 2}));
  EXPECT_DOUBLE_EQ(layers.exclusion(0, 0), 8.0);
  EXPECT_DOUBLE_EQ(layers.exclusion(2, 2), 1.5);
  const double trees_bushes = 1.0 / std::sqrt(1.0 / 64 + 1.0 / 9);
  const double with_rocks = 1.0 / std::sqrt(1.0 / 64 + 1.0 / 9 + 1.0 / 2.25);
  EXPECT_DOUBLE_EQ(layers.exclusion(0, 1), trees_bushes);
  EXPECT_DOUBLE_EQ(layers.exclusion(1, 0), trees_bushes);
  EXPECT_DOUBLE_EQ(layers.exclusion(0, 2), with_rocks);
  EXPECT_DOUBLE_EQ(layers.exclusion(1, 2), with_rocks);
  EXPECT_FALSE(layers.exclusion_given(0, 1));
  // Order by decreasing spacing whatever the spec's order; names keep their numbers.
  WorldSpec spec{.seed = 1};
  spec.layers = {{.name = "rocks", .min_distance = 1.5},
                 {.name = "trees", .min_distance = 8},
                 {.name = "also-rocks", .min_distance = 1.5}};
  const World shuffled = ValidWorld(spec);
  EXPECT_EQ(shuffled.layers()->generation_order(), (std::vector<int>{1, 0, 2}));
  EXPECT_EQ(shuffled.layers()->LayerNamed("also-rocks"), 2);
  // The first generated layer is the plain world of its spacing, with the world's seed.
  EXPECT_EQ(shuffled.layers()->world(1), ValidWorld({.seed = 1, .min_distance = 8}));
  EXPECT_EQ(shuffled.layers()->world(1).earlier_layers(), nullptr);
  EXPECT_NE(shuffled.layers()->world(0).earlier_layers(), nullptr);
}

TEST(LayeredWorldTest, BadSpecsNameTheField) {
  const auto error = [](const WorldSpec& spec) {
    StatusOr<World> world = World::Create(spec);
    EXPECT_FALSE(world.ok());
    return world.ok() ? std::string() : world.status().message();
  };
  const auto starts = [](const std::string& message, const std::string& field) {
    return message.rfind(field, 0) == 0;
  };
  WorldSpec base{.seed = 3};
  base.layers = {{.name = "trees", .min_distance = 8}, {.name = "bushes", .min_distance = 3}};

  WorldSpec asymmetric = base;
  asymmetric.exclusions = {{"trees", "bushes", 2.0}, {"bushes", "trees", 2.5}};
  const std::string message = error(asymmetric);
  EXPECT_TRUE(starts(message, "world.exclusions[1]: the matrix is not symmetric")) << message;
  WorldSpec symmetric = base;
  symmetric.exclusions = {{"trees", "bushes", 2.0}, {"bushes", "trees", 2.0}};
  EXPECT_TRUE(World::Create(symmetric).ok());
  WorldSpec twice = base;
  twice.exclusions = {{"trees", "bushes", 2.0}, {"trees", "bushes", 1.0}};
  EXPECT_TRUE(starts(error(twice), "world.exclusions[1]: the pair is given twice"));
  for (double bad : {-1.0, std::nan(""), double{INFINITY}, 33.0}) {
    WorldSpec spec = base;
    spec.exclusions = {{"trees", "bushes", bad}};
    EXPECT_TRUE(starts(error(spec), "world.exclusions[0].distance: must be in [0, 32]"));
  }
  WorldSpec unknown = base;
  unknown.exclusions = {{"trees", "ferns", 1.0}};
  EXPECT_TRUE(starts(error(unknown), "world.exclusions[0].second: no layer named 'ferns'"));
  WorldSpec self = base;
  self.exclusions = {{"trees", "trees", 8.0}};
  EXPECT_TRUE(starts(error(self), "world.exclusions[0]: pairs layer 'trees' with itself"));
  WorldSpec repeated = base;
  repeated.layers.push_back({.name = "trees", .min_distance = 1});
  EXPECT_TRUE(starts(error(repeated),
                     "world.layers[2].name: 'trees' is already the name of "
                     "world.layers[0]"));
  WorldSpec too_many{.seed = 3};
  for (int k = 0; k <= kMaxLayers; ++k) {
    // Not "l" + to_string(k): GCC 12 warns (-Wrestrict) on that concatenation, wrongly.
    std::string name(1, 'l');
    name.append(std::to_string(k));
    too_many.layers.push_back({.name = name, .min_distance = 1.0 + k});
  }
  EXPECT_TRUE(starts(error(too_many), "world.layers: at most 16 layers, got 17"));
  too_many.layers.pop_back();
  EXPECT_TRUE(World::Create(too_many).ok());
  WorldSpec bad_name = base;
  bad_name.layers[1].name = "two words";
  EXPECT_TRUE(starts(error(bad_name), "world.layers[1].name: must be 1 to 64 characters"));
  bad_name.layers[1].name = "";
  EXPECT_TRUE(starts(error(bad_name), "world.layers[1].name"));
  WorldSpec bad_spacing = base;
  bad_spacing.layers[1].min_distance = std::nan("");
  EXPECT_TRUE(starts(error(bad_spacing), "world.layers[1].min_distance: must be within"));
  WorldSpec bad_field = base;
  bad_field.layers[1].radius_field =
      RadiusFieldSpec{.kind = RadiusFieldKind::kNoise, .r_min = 2, .r_max = 1};
  EXPECT_TRUE(starts(error(bad_field), "world.layers[1].radius_field.r_max"));
  WorldSpec own_field = base;
  own_field.radius_field =
      RadiusFieldSpec{.kind = RadiusFieldKind::kConstant, .r_min = 1, .r_max = 1};
  EXPECT_TRUE(starts(error(own_field), "world.radius_field: a layered world"));
  WorldSpec a1 = base;
  a1.algorithm = WorldAlgorithm::kA1;
  EXPECT_TRUE(starts(error(a1), "world.algorithm: a world of several layers must use a3"));
  a1.layers.pop_back();
  EXPECT_TRUE(World::Create(a1).ok());
  WorldSpec no_layers{.seed = 3};
  no_layers.exclusions = {{"a", "b", 1.0}};
  EXPECT_TRUE(starts(error(no_layers), "world.layers"));
}

// A world of one layer is the plain world of its spacing: the same points and ids, layer 0.
TEST(LayeredWorldTest, OneLayerIsThePlainWorld) {
  PlaneEngine engine(EngineOptions(2, int64_t{64} << 20));
  for (const WorldAlgorithm algorithm : {WorldAlgorithm::kA3, WorldAlgorithm::kA1}) {
    WorldSpec spec{.seed = 7, .algorithm = algorithm};
    spec.layers = {{.name = "only", .min_distance = 2}};
    const World layered = ValidWorld(spec);
    const World plain = ValidWorld({.seed = 7, .min_distance = 2, .algorithm = algorithm});
    EXPECT_FALSE(layered == plain);
    EXPECT_EQ(layered.layers()->world(0), plain);
    const Rect rect{-50, -40, 60, 45};
    const PlanePoints a = MustPoints(engine, layered, rect);
    const PlanePoints b = MustPoints(engine, plain, rect);
    ASSERT_GT(a.positions.size(), 500u);
    EXPECT_EQ(a.ids, b.ids);
    ASSERT_EQ(a.positions.size(), b.positions.size());
    for (size_t k = 0; k < a.positions.size(); ++k) {
      EXPECT_EQ(a.positions[k].x, b.positions[k].x);
      EXPECT_EQ(a.positions[k].y, b.positions[k].y);
    }
    EXPECT_EQ(a.layers, std::vector<uint8_t>(a.positions.size(), 0));
    EXPECT_TRUE(b.layers.empty());
  }
}

// Windows on region corners of each layer (the trees' 128, the bushes' 18, the rocks' 9 wide):
// no pair closer than its rule, every layer maximal given the others, and the verifier agrees.
TEST(LayeredWorldTest, NoConflictAndEachLayerMaximalByBruteForce) {
  for (const bool field_bushes : {false, true}) {
    for (const uint64_t seed : {2u, 11u}) {
      const World world = Forest(seed, field_bushes);
      const WorldLayers& layers = *world.layers();
      PlaneEngine engine(EngineOptions(2, int64_t{64} << 20));
      Rng rng(HashWords({seed, field_bushes}));
      for (int trial = 0; trial < 3; ++trial) {
        // A corner of the trees' regions, of the bushes', then a random spot.
        const double side = RegionLayout(layers.world(trial == 1 ? 1 : 0)).side();
        const Vec2 corner = trial == 2 ? Vec2{rng.Uniform(-300, 300), rng.Uniform(-300, 300)}
                                       : Vec2{side * (static_cast<double>(rng.Below(3)) - 1),
                                              side * (static_cast<double>(rng.Below(3)) - 1)};
        const Rect window{corner.x - rng.Uniform(8, 14), corner.y - rng.Uniform(8, 14),
                          corner.x + rng.Uniform(8, 14), corner.y + rng.Uniform(8, 14)};
        SCOPED_TRACE(::testing::Message()
                     << "seed " << seed << (field_bushes ? " field bushes" : "") << " window ["
                     << window.x0 << ", " << window.x1 << ") x [" << window.y0 << ", " << window.y1
                     << ")");
        const PlanePoints halo = MustPoints(engine, world, Grown(window, 20.0));
        double worst_ratio = 0;
        EXPECT_EQ(BruteForceConflicts(halo, layers, window, &worst_ratio), 0);
        EXPECT_GE(worst_ratio, 1.0);
        std::vector<int64_t> per_layer(3, 0);
        for (const uint8_t layer : halo.layers) ++per_layer[layer];
        EXPECT_GT(per_layer[0], 2);
        EXPECT_GT(per_layer[1], 20);
        EXPECT_GT(per_layer[2], 50);
        for (int k = 0; k < 3; ++k) {
          const Probe probe = BruteForceGap(halo, layers, k, window, 0.3, seed + trial);
          EXPECT_LT(probe.worst, 1e-7) << "layer " << layers.name(k) << " uncovered at ("
                                       << probe.spot.x << ", " << probe.spot.y << ")";
        }
        StatusOr<VerifyReport> report = VerifyWorldRect(engine, world, window, QueryLimit{});
        ASSERT_TRUE(report.ok()) << report.status().message();
        ASSERT_TRUE(report->layered.has_value());
        EXPECT_TRUE(report->passed()) << "cross conflicts " << report->layered->cross_conflicts;
        EXPECT_GT(report->layered->cross_pairs_checked, 0);
      }
    }
  }
}

// A road masked in every layer (a raster of one radius whose road pixels are 0), and sixteen
// layers: no point on the road, none closer than its rule, each layer maximal given the others
// off the road; the verifier agrees.
TEST(LayeredWorldTest, MaskedRoadAndSixteenLayersByBruteForce) {
  auto road = std::make_shared<RasterImage>();
  road->width = 40;
  road->height = 40;
  for (int j = 0; j < road->height; ++j) {
    for (int i = 0; i < road->width; ++i) road->pixels.push_back(std::abs(i - j) < 3 ? 0 : 255);
  }
  const auto masked = [&](double r) {
    return RadiusFieldSpec{.kind = RadiusFieldKind::kRaster,
                           .r_min = r,
                           .r_max = r,
                           .raster = road,
                           .raster_origin = {-20, -20},
                           .pixel_size = 1};
  };
  WorldSpec with_road{.seed = 4};
  with_road.layers = {{.name = "trees", .radius_field = masked(8)},
                      {.name = "bushes", .radius_field = masked(3)},
                      {.name = "rocks", .radius_field = masked(1.5)}};
  WorldSpec sixteen{.seed = 9};
  for (int k = 0; k < kMaxLayers; ++k) {
    std::string name(1, 'l');
    name.append(std::to_string(k));
    sixteen.layers.push_back({.name = name, .min_distance = 6.0 * std::pow(0.85, k)});
  }
  for (const WorldSpec& spec : {with_road, sixteen}) {
    const World world = ValidWorld(spec);
    const WorldLayers& layers = *world.layers();
    PlaneEngine engine(EngineOptions(2, int64_t{64} << 20));
    // Sixteen layers cost sixteen probings: a smaller window.
    const Rect window = layers.count() > 3 ? Rect{-3, -5, 5, 3} : Rect{-9, -7, 7, 9};
    SCOPED_TRACE(world.Describe());
    const PlanePoints halo =
        MustPoints(engine, world, Grown(window, 2 * layers.largest_spacing() + 0.5));
    EXPECT_EQ(BruteForceConflicts(halo, layers, window), 0);
    int64_t on_the_road = 0;
    for (size_t m = 0; m < halo.positions.size(); ++m) {
      const RadiusField* field = layers.world(halo.layers[m]).radius_field();
      on_the_road += field != nullptr && field->IsMasked(halo.positions[m]);
    }
    EXPECT_EQ(on_the_road, 0);
    for (int k = 0; k < layers.count(); ++k) {
      const Probe probe = BruteForceGap(halo, layers, k, window, 0.25, 7);
      EXPECT_LT(probe.worst, 1e-7) << "layer " << layers.name(k) << " uncovered at ("
                                   << probe.spot.x << ", " << probe.spot.y << ")";
    }
    StatusOr<VerifyReport> report = VerifyWorldRect(engine, world, window, QueryLimit{});
    ASSERT_TRUE(report.ok()) << report.status().message();
    EXPECT_TRUE(report->passed());
  }
}

// Exclusion disks that overlap (big points at least 4 apart, each keeping small ones 3 away)
// leave the small layer pockets between them that no small point's circle reaches from another:
// A3 seeds each from the disks' circles (a point there lies at the disk's cut radius from its
// centre, which growth from a point's circle hits with probability 0). Over windows on the
// corners of both layers' regions: no pair closer than its rule and each layer maximal given
// the other, by brute force; the verifier agrees.
TEST(LayeredWorldTest, PocketsClosedByExclusionDisksAreFilled) {
  WorldSpec spec{.seed = 31};
  spec.layers = {{.name = "big", .min_distance = 4}, {.name = "small", .min_distance = 1}};
  spec.exclusions = {{.first = "big", .second = "small", .distance = 3.0}};
  const World world = ValidWorld(spec);
  const WorldLayers& layers = *world.layers();
  // A constant later layer is an A3 world of 16 d regions.
  EXPECT_EQ(layers.world(1).radius_field(), nullptr);
  EXPECT_EQ(RegionLayout(layers.world(1)).side(), 16.0);
  PlaneEngine engine(EngineOptions(2, int64_t{64} << 20));
  Rng rng(32);
  int64_t seeded_on_disks = 0;
  for (int trial = 0; trial < 4; ++trial) {
    const double side = RegionLayout(layers.world(trial % 2)).side();
    const Vec2 corner = {side * (static_cast<double>(rng.Below(3)) - 1),
                         side * (static_cast<double>(rng.Below(3)) - 1)};
    const Rect window{corner.x - rng.Uniform(6, 10), corner.y - rng.Uniform(6, 10),
                      corner.x + rng.Uniform(6, 10), corner.y + rng.Uniform(6, 10)};
    SCOPED_TRACE(::testing::Message() << "window [" << window.x0 << ", " << window.x1 << ") x ["
                                      << window.y0 << ", " << window.y1 << ")");
    const PlanePoints halo = MustPoints(engine, world, Grown(window, 10.0));
    EXPECT_EQ(BruteForceConflicts(halo, layers, window), 0);
    int64_t small = 0;
    for (size_t m = 0; m < halo.positions.size(); ++m) {
      if (halo.layers[m] != 1 || !window.Contains(halo.positions[m])) continue;
      ++small;
      for (size_t c = 0; c < halo.positions.size(); ++c) {
        if (halo.layers[c] != 0) continue;
        const double gap = std::sqrt(SquaredDistance(halo.positions[m], halo.positions[c])) - 3.0;
        seeded_on_disks += gap >= 0 && gap < 1e-8;
      }
    }
    EXPECT_GT(small, 10);
    for (int k = 0; k < 2; ++k) {
      const Probe probe = BruteForceGap(halo, layers, k, window, 0.2, 40 + trial);
      EXPECT_LT(probe.worst, 1e-7) << "layer " << layers.name(k) << " uncovered at ("
                                   << probe.spot.x << ", " << probe.spot.y << ")";
    }
    StatusOr<VerifyReport> report = VerifyWorldRect(engine, world, window, QueryLimit{});
    ASSERT_TRUE(report.ok()) << report.status().message();
    EXPECT_TRUE(report->passed());
  }
  EXPECT_GT(seeded_on_disks, 4);
}

// The verifier catches a bush moved onto a trunk and a rock removed (whenever brute force
// finds the gap its removal leaves beyond the tolerance).
TEST(LayeredWorldTest, PlantedFaultsAreCaught) {
  const World world = Forest(5);
  const WorldLayers& layers = *world.layers();
  PlaneEngine engine(EngineOptions(2, int64_t{64} << 20));
  const Rect window{-20, -20, 20, 20};
  const PlanePoints halo = MustPoints(engine, world, Grown(window, 20.0));
  std::vector<RadiusField> fields;
  std::vector<double> matrix;
  for (int a = 0; a < 3; ++a) {
    fields.push_back(RadiusField::Constant(layers.world(a).min_distance()));
    for (int b = 0; b < 3; ++b) matrix.push_back(layers.exclusion(a, b));
  }
  const auto judge = [&](const PlanePoints& points) {
    StatusOr<LayerVerifyReport> report =
        VerifyLayeredWindow(points.positions, points.layers, window, fields, matrix);
    EXPECT_TRUE(report.ok()) << report.status().message();
    return *report;
  };
  ASSERT_TRUE(judge(halo).passed());
  std::vector<size_t> trees, bushes, rocks;
  for (size_t k = 0; k < halo.positions.size(); ++k) {
    if (!Grown(window, -3).Contains(halo.positions[k])) continue;
    (halo.layers[k] == 0 ? trees : halo.layers[k] == 1 ? bushes : rocks).push_back(k);
  }
  ASSERT_FALSE(trees.empty());
  ASSERT_GT(bushes.size(), 5u);
  ASSERT_GT(rocks.size(), 20u);
  // A bush moved onto a trunk (1 from it, within D = 2.81).
  {
    PlanePoints moved = halo;
    const Vec2 trunk = halo.positions[trees.front()];
    moved.positions[bushes.front()] = {trunk.x + 1.0, trunk.y};
    const LayerVerifyReport report = judge(moved);
    EXPECT_GT(report.cross_conflicts, 0);
    EXPECT_EQ(report.cross_conflicts,
              BruteForceConflicts(moved, layers, window) - report.layers[1].conflicts);
    EXPECT_FALSE(report.passed());
  }
  // Rocks removed one at a time.
  int judged = 0;
  Rng rng(8);
  for (int trial = 0; trial < 10; ++trial) {
    const size_t k = rocks[rng.Below(rocks.size())];
    PlanePoints removed = halo;
    const Vec2 spot = removed.positions[k];
    removed.positions.erase(removed.positions.begin() + static_cast<std::ptrdiff_t>(k));
    removed.layers.erase(removed.layers.begin() + static_cast<std::ptrdiff_t>(k));
    const Probe probe =
        BruteForceGap(removed, layers, 2, Grown(Rect{spot.x, spot.y, spot.x, spot.y}, 0.75), 0.05,
                      static_cast<uint64_t>(trial));
    const LayerVerifyReport report = judge(removed);
    EXPECT_EQ(report.cross_conflicts, 0);
    EXPECT_GE(report.layers[2].gap_bound, probe.worst - 1e-12);
    if (probe.worst > 1e-8 * 1.5) {
      ++judged;
      EXPECT_FALSE(report.passed()) << "removed rock (" << spot.x << ", " << spot.y << ")";
    }
  }
  EXPECT_GE(judged, 5);
}

// The same points, ids and layers for any tiling, query order, thread count and cache size,
// and with a layer filter the unfiltered answer filtered.
TEST(LayeredWorldTest, DeterministicForAnyTilingOrderThreadsAndCache) {
  const World world = Forest(21, true);
  const Rect query{-70, -50, 90, 70};
  using Key = std::tuple<uint8_t, uint64_t, double, double>;
  const auto keys = [](const PlanePoints& points, const Rect& rect) {
    std::vector<Key> out;
    for (size_t k = 0; k < points.positions.size(); ++k) {
      if (!rect.Contains(points.positions[k])) continue;
      out.emplace_back(points.layers[k], points.ids[k], points.positions[k].x,
                       points.positions[k].y);
    }
    std::sort(out.begin(), out.end());
    return out;
  };
  PlaneEngine reference_engine(EngineOptions(1, int64_t{256} << 20));
  const PlanePoints reference = MustPoints(reference_engine, world, query);
  const std::vector<Key> expected = keys(reference, query);
  ASSERT_GT(expected.size(), 2000u);
  Rng rng(1234);
  for (const auto& [threads, cache] :
       {std::pair{1, int64_t{256} << 20}, std::pair{3, int64_t{256} << 20},
        std::pair{2, int64_t{0}}}) {
    PlaneEngine engine(EngineOptions(threads, cache));
    // Random tiles in a random order.
    std::vector<double> xs{query.x0, query.x1}, ys{query.y0, query.y1};
    for (int n = 0; n < 3; ++n) xs.push_back(rng.Uniform(query.x0, query.x1));
    for (int n = 0; n < 2; ++n) ys.push_back(rng.Uniform(query.y0, query.y1));
    std::vector<Key> got;
    for (const Rect& tile : ShuffledTiles(xs, ys, rng)) {
      const std::vector<Key> part = keys(MustPoints(engine, world, tile), tile);
      got.insert(got.end(), part.begin(), part.end());
    }
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, expected) << threads << " threads, cache " << cache;
  }
  // A layer filter: the unfiltered answer, filtered.
  PlaneEngine engine(EngineOptions(2, int64_t{64} << 20));
  const PlanePoints rocks_and_trees = MustPoints(engine, world, query, 0b101);
  std::vector<Key> filtered;
  for (const Key& key : expected) {
    if (std::get<0>(key) != 1) filtered.push_back(key);
  }
  EXPECT_EQ(keys(rocks_and_trees, query), filtered);
  StatusOr<int64_t> count = engine.Count(world, query);
  ASSERT_TRUE(count.ok());
  EXPECT_EQ(*count, static_cast<int64_t>(expected.size()));
  // A layered world has no regions of its own.
  EXPECT_FALSE(engine.Regions(world, query).ok());
}

}  // namespace
}  // namespace scallop
