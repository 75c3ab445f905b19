// AreaSumTree implementation.
#include "scallop/sampling/area_sum_tree.h"

#include <bit>
#include <cstdint>

namespace scallop {

void AreaSumTree::Set(size_t index, double weight) {
  if (index >= leaves_) {
    size_t leaves = leaves_ == 0 ? 1024 : leaves_;
    while (leaves <= index) leaves *= 2;
    std::vector<double> nodes(2 * leaves, 0.0);
    for (size_t i = 0; i < leaves_; ++i) nodes[leaves + i] = nodes_[leaves_ + i];
    for (size_t node = leaves - 1; node >= 1; --node) nodes[node] = nodes[2 * node] + nodes[2 * node + 1];
    nodes_.swap(nodes);
    leaves_ = leaves;
  }
  size_t node = leaves_ + index;
  // The sums are a pure function of the leaves, so an unchanged leaf (most cuts of a neighbour
  // miss it) leaves every node as it is; comparing bits also tells -0 from +0.
  if (std::bit_cast<uint64_t>(nodes_[node]) == std::bit_cast<uint64_t>(weight)) return;
  nodes_[node] = weight;
  for (node /= 2; node >= 1; node /= 2) nodes_[node] = nodes_[2 * node] + nodes_[2 * node + 1];
}

size_t AreaSumTree::Pick(double u) const {
  double target = u * Total();
  size_t node = 1;
  while (node < leaves_) {
    const double left = nodes_[2 * node], right = nodes_[2 * node + 1];
    // Going right past a rounding-sized target must not land on zero weight.
    if (right <= 0.0 || (left > 0.0 && target < left)) {
      node = 2 * node;
    } else {
      target -= left;
      node = 2 * node + 1;
    }
  }
  return node - leaves_;
}

}  // namespace scallop
