// AreaSumTree: a complete binary tree of sums over per-point weights, so A1
// can pick a neighbourhood with probability proportional to its area in
// O(log N). Each inner node is recomputed as left + right on every update,
// so no rounding drift accumulates, and the choice is a pure function of the
// weights and the random number.
#pragma once

#include <cstddef>
#include <vector>

namespace scallop {

class AreaSumTree {
 public:
  // Sets weight i (>= 0), growing the tree as needed. O(log N) amortised; O(1) when weight i
  // already has these bits.
  void Set(size_t index, double weight);

  double Total() const { return nodes_.empty() ? 0.0 : nodes_[1]; }

  // The index whose cumulative weight range holds u * Total(), u in [0, 1).
  // Never returns an index of weight 0. REQUIRES: Total() > 0. O(log N).
  size_t Pick(double u) const;

 private:
  size_t leaves_ = 0;          // a power of two; leaf i is nodes_[leaves_ + i]
  std::vector<double> nodes_;  // nodes_[1] is the root; nodes_[0] unused
};

}  // namespace scallop
