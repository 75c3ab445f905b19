// Wei's multi-class dart throwing (SampleMultiClassDarts), the baseline the ordered layers are
// compared against: every pair under the exclusion matrix by brute force (tests/layer_checks.h),
// on random domains and seeds (printed); the classes filled alike toward their targets; the
// removal rule filling more than plain multi-class darts; targets met exactly when they are
// easy; the same bits for the same options; bad options named.
#include "scallop/sampling/multiclass_darts.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "scallop/plane/world_layers.h"
#include "scallop/random/rng.h"
#include "tests/layer_checks.h"

namespace scallop {
namespace {

// Wei's options for the forest on `domain`, aiming at the counts the ordered layers reach there.
MultiClassDartOptions ForestDarts(const World& forest, const Rect& domain, uint64_t seed) {
  MultiClassDartOptions options;
  options.layers = BoundedLayersOn(*forest.layers(), domain);
  StatusOr<LayeredPoints> ordered = SampleLayers(options.layers);
  EXPECT_TRUE(ordered.ok()) << ordered.status().message();
  options.targets.assign(3, 0);
  if (ordered.ok()) {
    for (uint8_t layer : ordered->layers) ++options.targets[layer];
  }
  options.failure_limit = 20000;
  options.seed = seed;
  return options;
}

PlanePoints Darts(const MultiClassDartOptions& options) {
  StatusOr<LayeredPoints> sampled = SampleMultiClassDarts(options);
  EXPECT_TRUE(sampled.ok()) << sampled.status().message();
  return sampled.ok() ? AsPlanePoints(*sampled) : PlanePoints{};
}

std::vector<int64_t> PerLayer(const PlanePoints& points) {
  std::vector<int64_t> counts(3, 0);
  for (uint8_t layer : points.layers) ++counts[layer];
  return counts;
}

TEST(MultiClassDartsTest, EveryPairKeepsItsRule) {
  for (int trial = 0; trial < 4; ++trial) {
    const uint64_t seed = 300 + static_cast<uint64_t>(trial);
    SCOPED_TRACE("seed " + std::to_string(seed));
    Rng dice(seed);
    const double x0 = dice.Uniform(-1e4, 1e4), y0 = dice.Uniform(-1e4, 1e4);
    const Rect domain{x0, y0, x0 + dice.Uniform(35, 55), y0 + dice.Uniform(35, 55)};
    const World forest = Forest(seed);
    const PlanePoints points = Darts(ForestDarts(forest, domain, seed));
    for (const Vec2& p : points.positions) ASSERT_TRUE(domain.Contains(p));
    for (int64_t count : PerLayer(points)) EXPECT_GT(count, 0);
    EXPECT_EQ(BruteForceConflicts(points, *forest.layers(), domain), 0);
    // The check sees a bush moved onto a tree.
    PlanePoints planted = points;
    const auto tree = std::find(planted.layers.begin(), planted.layers.end(), 0);
    const auto bush = std::find(planted.layers.begin(), planted.layers.end(), 1);
    ASSERT_TRUE(tree != planted.layers.end() && bush != planted.layers.end());
    planted.positions[static_cast<size_t>(bush - planted.layers.begin())] =
        planted.positions[static_cast<size_t>(tree - planted.layers.begin())] + Vec2{1.0, 0.0};
    EXPECT_GT(BruteForceConflicts(planted, *forest.layers(), domain), 0);
  }
}

// A dart goes to the class furthest below its target, so the classes end at about the same
// fraction of their targets: within a point or two of the least filled.
TEST(MultiClassDartsTest, FillsTheClassesAlike) {
  const World forest = Forest(11);
  const Rect domain{0, 0, 80, 80};
  const MultiClassDartOptions options = ForestDarts(forest, domain, 11);
  const std::vector<int64_t> counts = PerLayer(Darts(options));
  double least = 1.0, most = 0.0, step = 0.0;
  for (size_t c = 0; c < 3; ++c) {
    const double fill = static_cast<double>(counts[c]) / static_cast<double>(options.targets[c]);
    least = std::min(least, fill);
    most = std::max(most, fill);
    step = std::max(step, 1.0 / static_cast<double>(options.targets[c]));
    SCOPED_TRACE("class " + std::to_string(c) + ": " + std::to_string(counts[c]) + " of " +
                 std::to_string(options.targets[c]));
  }
  EXPECT_GT(least, 0.5);  // dart throwing stops short of the maximal ordered counts
  EXPECT_LT(least, 1.0);
  EXPECT_LE(most - least, 2 * step) << "fills from " << least << " to " << most;
}

// Without removal a tree's dart fails wherever bushes and rocks already sit, so every class
// stops lower: the removal rule is what lets the large class fill.
TEST(MultiClassDartsTest, RemovalFillsMoreThanPlainDarts) {
  for (const uint64_t seed : {21u, 22u, 23u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const World forest = Forest(seed);
    MultiClassDartOptions options = ForestDarts(forest, Rect{0, 0, 60, 60}, seed);
    const std::vector<int64_t> with = PerLayer(Darts(options));
    options.removal = false;
    const PlanePoints plain = Darts(options);
    EXPECT_EQ(BruteForceConflicts(plain, *forest.layers(), Rect{0, 0, 60, 60}), 0);
    const std::vector<int64_t> without = PerLayer(plain);
    EXPECT_GT(with[0], without[0]);
    EXPECT_GT(with[0] + with[1] + with[2], without[0] + without[1] + without[2]);
  }
}

TEST(MultiClassDartsTest, StopsAtEasyTargets) {
  const World forest = Forest(5);
  MultiClassDartOptions options = ForestDarts(forest, Rect{0, 0, 50, 50}, 5);
  options.targets = {3, 10, 40};
  EXPECT_EQ(PerLayer(Darts(options)), (std::vector<int64_t>{3, 10, 40}));
}

TEST(MultiClassDartsTest, SameOptionsSameBits) {
  const World forest = Forest(8);
  MultiClassDartOptions options = ForestDarts(forest, Rect{0, 0, 40, 40}, 8);
  const PlanePoints first = Darts(options);
  const PlanePoints again = Darts(options);
  EXPECT_EQ(first.positions, again.positions);
  EXPECT_EQ(first.layers, again.layers);
  options.seed = 9;
  EXPECT_NE(Darts(options).positions, first.positions);
}

TEST(MultiClassDartsTest, BadOptionsAreNamed) {
  const World forest = Forest(4);
  const MultiClassDartOptions good = ForestDarts(forest, Rect{0, 0, 40, 40}, 4);
  const auto message = [](const MultiClassDartOptions& options) {
    StatusOr<LayeredPoints> sampled = SampleMultiClassDarts(options);
    EXPECT_FALSE(sampled.ok());
    return sampled.ok() ? std::string() : sampled.status().message();
  };
  MultiClassDartOptions bad = good;
  bad.targets.pop_back();
  EXPECT_NE(message(bad).find("targets"), std::string::npos);
  bad = good;
  bad.targets[1] = 0;
  EXPECT_NE(message(bad).find("targets[1]"), std::string::npos);
  bad = good;
  bad.targets[2] = kMaxMultiClassTarget + 1;
  EXPECT_NE(message(bad).find("targets[2]"), std::string::npos);
  bad = good;
  bad.failure_limit = 0;
  EXPECT_NE(message(bad).find("failure_limit"), std::string::npos);
  bad = good;
  bad.layers.exclusions[1] = -1;
  EXPECT_NE(message(bad).find("exclusions[1]"), std::string::npos);
  const World field_forest = Forest(4, /*field_bushes=*/true);
  bad = good;
  bad.layers = BoundedLayersOn(*field_forest.layers(), Rect{0, 0, 40, 40});
  EXPECT_NE(message(bad).find("layers.layers[1].field"), std::string::npos);
}

}  // namespace
}  // namespace scallop
