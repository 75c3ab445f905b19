// The bounded layered sampler (SampleLayers, issue 19), judged on its real output by brute force
// written apart from it (tests/layer_checks.h): every pair under the exclusion matrix and each
// layer's largest empty spot over the whole domain, for random domains and seeds (printed), with
// constant and field layers; planted faults the checks must catch (layers sampled without their
// disks, a point removed); a constant layer sampled first equal to Sample's A3; bad options named.
#include "scallop/sampling/layered_sampler.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "scallop/plane/world_layers.h"
#include "scallop/random/rng.h"
#include "scallop/sampling/sampler.h"
#include "tests/field_test_fields.h"
#include "tests/layer_checks.h"
#include "tests/test_worlds.h"

namespace scallop {
namespace {

PlanePoints Sampled(const LayeredSamplerOptions& options) {
  StatusOr<LayeredPoints> sampled = SampleLayers(options);
  EXPECT_TRUE(sampled.ok()) << sampled.status().message();
  return sampled.ok() ? AsPlanePoints(*sampled) : PlanePoints{};
}

// The domain less a hair: a spot on the far edges of a half-open rectangle can be approached by
// points, never reached.
Rect Probed(const Rect& domain) { return Grown(domain, -1e-6); }

// A random domain of 35 to 55 a side, anywhere within 1e4 of the origin.
Rect RandomDomain(Rng& dice) {
  const double x0 = dice.Uniform(-1e4, 1e4), y0 = dice.Uniform(-1e4, 1e4);
  return {x0, y0, x0 + dice.Uniform(35, 55), y0 + dice.Uniform(35, 55)};
}

TEST(LayeredSamplerTest, EveryPairKeepsItsRuleAndEveryLayerIsMaximal) {
  for (const bool field_bushes : {false, true}) {
    for (int trial = 0; trial < 3; ++trial) {
      const uint64_t seed = 100 + static_cast<uint64_t>(trial);
      SCOPED_TRACE("seed " + std::to_string(seed) + (field_bushes ? ", field bushes" : ""));
      Rng dice(seed);
      const World world = Forest(seed, field_bushes);
      const WorldLayers& layers = *world.layers();
      const Rect domain = RandomDomain(dice);
      const PlanePoints points = Sampled(BoundedLayersOn(layers, domain));
      std::vector<int> per_layer(3, 0);
      for (size_t k = 0; k < points.positions.size(); ++k) {
        ASSERT_TRUE(domain.Contains(points.positions[k]));
        ++per_layer[points.layers[k]];
      }
      for (int k = 0; k < 3; ++k) EXPECT_GT(per_layer[k], 0) << layers.name(k);
      EXPECT_EQ(BruteForceConflicts(points, layers, domain), 0);
      for (int k = 0; k < layers.count(); ++k) {
        const Probe probe = BruteForceGap(points, layers, k, Probed(domain), 0.3, seed);
        EXPECT_LT(probe.worst, 1e-7) << "layer " << layers.name(k) << " uncovered at ("
                                     << probe.spot.x << ", " << probe.spot.y << ")";
      }
    }
  }
}

TEST(LayeredSamplerTest, ChecksCatchPlantedFaults) {
  const World world = Forest(7, false);
  const WorldLayers& layers = *world.layers();
  const Rect domain{0, 0, 50, 50};
  LayeredSamplerOptions options = BoundedLayersOn(layers, domain);
  // Each layer sampled as if alone: its points enter the earlier layers' disks.
  LayeredSamplerOptions blind = options;
  for (double& distance : blind.exclusions) distance = 0.0;
  EXPECT_GT(BruteForceConflicts(Sampled(blind), layers, domain), 0);
  // The rocks within 2 of a rock clear of the other layers by 0.3 more than their D, removed:
  // a hole of the rocks' layer around it. (One rock removed alone can leave no spot free: A3
  // puts its neighbours on its circle.)
  PlanePoints points = Sampled(options);
  const auto clear_of_others = [&](Vec2 p) {
    for (size_t m = 0; m < points.positions.size(); ++m) {
      const double room = layers.exclusion(points.layers[m], 2) + 0.3;
      if (points.layers[m] != 2 && SquaredDistance(p, points.positions[m]) < room * room) {
        return false;
      }
    }
    return true;
  };
  size_t rock = 0;
  while (points.layers[rock] != 2 || !Grown(domain, -5).Contains(points.positions[rock]) ||
         !clear_of_others(points.positions[rock])) {
    ++rock;
  }
  const Vec2 spot = points.positions[rock];
  PlanePoints holed;
  for (size_t m = 0; m < points.positions.size(); ++m) {
    if (points.layers[m] == 2 && SquaredDistance(spot, points.positions[m]) < 4.0) continue;
    holed.positions.push_back(points.positions[m]);
    holed.layers.push_back(points.layers[m]);
  }
  EXPECT_GT(
      BruteForceGap(holed, layers, 2, Grown(Rect{spot.x, spot.y, spot.x, spot.y}, 0.75), 0.05, 1)
          .worst,
      0.2);
}

TEST(LayeredSamplerTest, ConstantLayerSampledFirstIsSamplesA3) {
  const World world = Forest(11, false);
  const Rect domain{-30, 5, 45, 70};
  const LayeredSamplerOptions options = BoundedLayersOn(*world.layers(), domain);
  const PlanePoints points = Sampled(options);
  const BoundedLayer& trees = options.layers[static_cast<size_t>(options.order[0])];
  StatusOr<std::vector<Vec2>> alone = Sample({.algorithm = Algorithm::kA3,
                                              .domain = {domain, false},
                                              .min_distance = trees.min_distance,
                                              .seed = trees.seed});
  ASSERT_TRUE(alone.ok());
  std::vector<Vec2> first;
  for (size_t k = 0; k < points.positions.size(); ++k) {
    if (points.layers[k] == options.order[0]) first.push_back(points.positions[k]);
  }
  EXPECT_EQ(first, *alone);
}

TEST(LayeredSamplerTest, SameOptionsSameBitsAndSeedsMatter) {
  const World world = Forest(5, true);
  const LayeredSamplerOptions options = BoundedLayersOn(*world.layers(), {0, 0, 40, 40});
  const PlanePoints a = Sampled(options), b = Sampled(options);
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.layers, b.layers);
  LayeredSamplerOptions reseeded = options;
  reseeded.layers[2].seed += 1;
  const PlanePoints c = Sampled(reseeded);
  EXPECT_NE(a.positions, c.positions);
}

TEST(LayeredSamplerTest, BadOptionsAreNamed) {
  const World world = Forest(3, false);
  const LayeredSamplerOptions good = BoundedLayersOn(*world.layers(), {0, 0, 20, 20});
  const auto message = [](const LayeredSamplerOptions& options) {
    const Status status = ValidateLayeredSamplerOptions(options);
    EXPECT_EQ(status.code(), StatusCode::kInvalidArgument);
    return status.message();
  };
  LayeredSamplerOptions bad = good;
  bad.layers.clear();
  EXPECT_NE(message(bad).find("layers: "), std::string::npos);
  bad = good;
  bad.layers[1].min_distance = 0;
  EXPECT_NE(message(bad).find("layers[1]: min_distance"), std::string::npos);
  bad = good;
  bad.domain = {0, 0, NAN, 20};
  EXPECT_NE(message(bad).find("layers[0]: domain"), std::string::npos);
  bad = good;
  bad.order = {0, 0, 2};
  EXPECT_NE(message(bad).find("order[1]"), std::string::npos);
  bad = good;
  bad.order = {0, 1};
  EXPECT_NE(message(bad).find("order: "), std::string::npos);
  bad = good;
  bad.exclusions[1] = 2.0;  // D[0][1] no longer D[1][0]
  EXPECT_NE(message(bad).find("exclusions[1]: the matrix must be symmetric"), std::string::npos);
  bad = good;
  bad.exclusions[5] = bad.exclusions[7] = -1.0;
  EXPECT_NE(message(bad).find("exclusions[5]: must be finite"), std::string::npos);
  bad = good;
  bad.exclusions[1] = bad.exclusions[3] = 4 * 8 + 1;  // trees (8) and bushes (3): at most 32
  EXPECT_NE(message(bad).find("exclusions[1]: at most 4 times"), std::string::npos);
  bad.exclusions[1] = bad.exclusions[3] = 4 * 8;
  EXPECT_TRUE(ValidateLayeredSamplerOptions(bad).ok());
  bad = good;
  bad.exclusions.pop_back();
  EXPECT_NE(message(bad).find("exclusions: "), std::string::npos);
  EXPECT_FALSE(SampleLayers(bad).ok());
  EXPECT_TRUE(ValidateLayeredSamplerOptions(good).ok());
}

}  // namespace
}  // namespace scallop
