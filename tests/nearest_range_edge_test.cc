// The bounds docs/noise.md promises for F1 and F2, checked where they change:
// at the precision limit, beyond which the world has no points (issue 20,
// item 6: the old promise of F1 < d "including on the limit itself" failed
// for 6-14% of positions on it, up to F1 = 1.71 d).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include "scallop/noise/nearest_lookup.h"
#include "scallop/plane/world_verifier.h"
#include "scallop/random/rng.h"
#include "tests/test_worlds.h"

namespace scallop::testing {
namespace {

// Where a position lies, by its distance from the limit in units of
// r = d (1 + tol): what decides which bound docs/noise.md promises.
enum class Zone {
  kInside,  // both coordinates at least 2 r inside: F1 < r, F1 + F2 < 2 r
  kEdge,    // one coordinate at least r inside: F1 < 2 r
  kCorner,  // anywhere in the range: F1 < (1 + sqrt 2) r
};

struct Sample {
  Vec2 position;
  Zone zone;
};

// Positions within 40 d of the range's four corners, each zone well
// represented, including exactly on the limit.
std::vector<Sample> Samples(Rng& rng, double d, double limit, double r) {
  std::vector<Sample> samples;
  for (double sx : {-1.0, 1.0}) {
    for (double sy : {-1.0, 1.0}) {
      samples.push_back({{sx * limit, sy * limit}, Zone::kCorner});
      for (int k = 0; k < 60; ++k) {
        const double near_x = limit - rng.Uniform(0, 3 * d);
        const double near_y = limit - rng.Uniform(0, 3 * d);
        const double far_y = limit - rng.Uniform(2 * r, 40 * d);
        const double far_x = limit - rng.Uniform(2 * r, 40 * d);
        samples.push_back({{sx * near_x, sy * near_y}, Zone::kCorner});
        samples.push_back({{sx * limit, sy * far_y}, Zone::kEdge});  // on the limit
        samples.push_back({{sx * near_x, sy * far_y}, Zone::kEdge});
        samples.push_back({{sx * far_x, sy * limit}, Zone::kEdge});
        samples.push_back({{sx * far_x, sy * far_y}, Zone::kInside});
      }
    }
  }
  return samples;
}

TEST(NearestRangeEdgeTest, PromisedBoundsHoldUpToAndOnTheLimit) {
  PlaneEngine engine({.threads = 1});
  NearestLookup lookup(engine);
  int violations = 0;
  for (WorldAlgorithm algorithm : {WorldAlgorithm::kA1, WorldAlgorithm::kA2, WorldAlgorithm::kA3}) {
    for (uint64_t seed : {61, 62}) {
      const World world = ValidWorld({.seed = seed,
                                      .min_distance = 1.0,
                                      .algorithm = algorithm,
                                      .density = algorithm == WorldAlgorithm::kA2 ? 1.5 : 2.0});
      const double d = world.min_distance();
      const double limit = RegionLayout(d).precision_limit();
      const double r = d * (1 + MaximalityTolerance(d, limit));
      Rng rng(HashWords({seed, static_cast<uint64_t>(algorithm)}));
      const std::vector<Sample> samples = Samples(rng, d, limit, r);
      std::vector<Vec2> positions;
      for (const Sample& sample : samples) positions.push_back(sample.position);
      std::vector<NearestPoint> results(positions.size());
      ASSERT_TRUE(lookup.Nearest(world, positions, results).ok());
      double worst_inside = 0, worst_sum = 0, worst_edge = 0, worst_corner = 0;
      int on_limit_beyond_d = 0;
      for (size_t k = 0; k < samples.size(); ++k) {
        const double f1 = results[k].f1, f2 = results[k].f2;
        const Vec2 p = samples[k].position;
        if (std::max(std::abs(p.x), std::abs(p.y)) == limit && f1 >= d) ++on_limit_beyond_d;
        switch (samples[k].zone) {
          case Zone::kInside:
            worst_inside = std::max(worst_inside, f1);
            worst_sum = std::max(worst_sum, f1 + f2);
            if (!(f1 < r && f1 + f2 < 2 * r)) ++violations;
            break;
          case Zone::kEdge:
            worst_edge = std::max(worst_edge, f1);
            if (!(f1 < 2 * r)) ++violations;
            break;
          case Zone::kCorner:
            worst_corner = std::max(worst_corner, f1);
            if (!(f1 < (1 + std::sqrt(2.0)) * r)) ++violations;
            break;
        }
      }
      std::cout << WorldAlgorithmName(algorithm) << " seed " << seed << ": largest F1 inside "
                << worst_inside << " d (F1 + F2 " << worst_sum << " d), near an edge " << worst_edge
                << " d, near a corner " << worst_corner << " d; " << on_limit_beyond_d
                << " positions on the limit with F1 >= d\n";
    }
  }
  EXPECT_EQ(violations, 0);
}

}  // namespace
}  // namespace scallop::testing
