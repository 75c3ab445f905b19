// Tests for AreaSumTree against brute force: after any sequence of Set calls (including ones
// that write a leaf's current value again, which Set skips) the tree must equal one built from
// scratch from the final weights, bit for bit, and Pick must land where a linear scan says.
#include "scallop/sampling/area_sum_tree.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "scallop/random/rng.h"

namespace scallop {
namespace {

// A tree built by setting every weight once, in index order.
AreaSumTree FreshTree(const std::vector<double>& weights) {
  AreaSumTree tree;
  for (size_t i = 0; i < weights.size(); ++i) tree.Set(i, weights[i]);
  return tree;
}

// The index a linear scan over the weights picks for target u * total (weights of 0 skipped).
size_t LinearPick(const std::vector<double>& weights, const AreaSumTree& tree, double u) {
  double target = u * tree.Total();
  size_t last_positive = 0;
  for (size_t i = 0; i < weights.size(); ++i) {
    if (weights[i] <= 0.0) continue;
    last_positive = i;
    if (target < weights[i]) return i;
    target -= weights[i];
  }
  return last_positive;
}

// A random history of Set calls over `count` leaves, many rewriting a leaf's current value.
std::vector<double> ApplyRandomHistory(Rng& rng, AreaSumTree& tree, size_t count) {
  std::vector<double> weights(count, 0.0);
  for (int step = 0; step < 20000; ++step) {
    const size_t i = rng.Below(count);
    switch (rng.Below(4)) {
      case 0:
        break;  // the same value again
      case 1:
        weights[i] = 0.0;
        break;
      case 2:
        weights[i] = rng.Uniform();
        break;
      default:
        weights[i] = weights[i] * 0.5;
        break;  // tiny and subnormal values too
    }
    tree.Set(i, weights[i]);
  }
  return weights;
}

TEST(AreaSumTreeTest, RepeatedSetsLeaveTheSameTreeAsAFreshBuild) {
  for (uint64_t seed = 1; seed <= 40; ++seed) {
    Rng rng(seed);
    AreaSumTree tree;
    const size_t count = 1 + rng.Below(3000);
    const std::vector<double> weights = ApplyRandomHistory(rng, tree, count);
    const AreaSumTree fresh = FreshTree(weights);
    ASSERT_EQ(std::bit_cast<uint64_t>(tree.Total()), std::bit_cast<uint64_t>(fresh.Total()))
        << "seed " << seed;
    if (!(tree.Total() > 0.0)) continue;
    for (int k = 0; k < 200; ++k) {
      const double u = rng.Uniform();
      ASSERT_EQ(tree.Pick(u), fresh.Pick(u)) << "seed " << seed << " u " << u;
      // Rounding in the partial sums may move a pick across a boundary only where the scan's
      // own sums disagree with the tree's, never onto a zero weight.
      ASSERT_GT(weights[tree.Pick(u)], 0.0) << "seed " << seed;
    }
  }
}

TEST(AreaSumTreeTest, PickMatchesALinearScanOnExactWeights) {
  // Weights that are multiples of 2^-10 sum exactly in any order, so tree and scan agree.
  Rng rng(5);
  AreaSumTree tree;
  std::vector<double> weights(777, 0.0);
  for (int step = 0; step < 5000; ++step) {
    const size_t i = rng.Below(weights.size());
    weights[i] = static_cast<double>(rng.Below(5)) * 0x1p-10;
    tree.Set(i, weights[i]);
  }
  for (int k = 0; k < 2000; ++k) {
    const double u = rng.Uniform();
    ASSERT_EQ(tree.Pick(u), LinearPick(weights, tree, u)) << "u " << u;
  }
}

// Planted fault: a Set that wrongly skips a changed leaf (as a skip on nearly equal values
// would) leaves a tree that the fresh-build comparison tells apart.
TEST(AreaSumTreeTest, FreshBuildComparisonCatchesASkippedUpdate) {
  std::vector<double> weights = {0.25, 0.5, 0.125};
  AreaSumTree faulty = FreshTree(weights);
  weights[1] = std::nextafter(0.5, 1.0);  // the update a faulty skip would drop
  EXPECT_NE(std::bit_cast<uint64_t>(faulty.Total()),
            std::bit_cast<uint64_t>(FreshTree(weights).Total()));
}

}  // namespace
}  // namespace scallop
