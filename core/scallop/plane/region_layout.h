// How a world cuts the plane into regions: square regions of side S = 16 d,
// region (i, j) owning [i S, (i+1) S) x [j S, (j+1) S), each with a rank that
// fixes which neighbours it depends on. See docs/design.md, "Regions".
#pragma once

#include <cmath>
#include <compare>
#include <cstdint>

#include "scallop/base/precision_range.h"
#include "scallop/geometry/rect.h"

namespace scallop {

// Region side in units of d. 16 d holds about 220 A3 points and leaves room
// for the growth margin of region_generator.h: every point that constrains a
// region lies within its 8 neighbours.
inline constexpr double kRegionSideInD = 16.0;

// Regions -2^28 .. 2^28 - 1 on each axis tile exactly [-2^32 d, 2^32 d).
inline constexpr auto kRegionsPerHalfAxis =
    static_cast<int64_t>(kPrecisionRangeInD / kRegionSideInD);

struct RegionKey {
  int64_t i = 0;
  int64_t j = 0;
  friend constexpr auto operator<=>(const RegionKey&, const RegionKey&) = default;
};

// Rank by parity (floor-mod, so negative indices work): (0,0) -> 0,
// (1,0) -> 1, (1,1) -> 2, (0,1) -> 3. A proper colouring of the king's graph:
// 8-neighbours never share a rank, so a region depends only on its
// lower-ranked neighbours and same-rank regions can be generated in parallel.
constexpr int RegionRank(RegionKey key) {
  const int x = static_cast<int>(key.i & 1), y = static_cast<int>(key.j & 1);
  return y == 0 ? x : 3 - x;
}

class RegionLayout {
 public:
  // REQUIRES: min_distance finite and > 0.
  explicit RegionLayout(double min_distance)
      : min_distance_(min_distance), side_(kRegionSideInD * min_distance) {}

  double side() const { return side_; }
  double precision_limit() const { return kPrecisionRangeInD * min_distance_; }

  // The half-open rectangle region `key` owns. Both ends of every edge are
  // computed by one expression, so adjacent regions share edges exactly.
  Rect RegionRect(RegionKey key) const {
    return {Edge(key.i), Edge(key.j), Edge(key.i + 1), Edge(key.j + 1)};
  }

  // The index of the region column (or row) owning coordinate v: the k with
  // Edge(k) <= v < Edge(k + 1), exactly, whatever floor(v / S) rounds to.
  int64_t IndexOf(double v) const {
    auto k = static_cast<int64_t>(std::floor(v / side_));
    if (v < Edge(k)) --k;
    if (v >= Edge(k + 1)) ++k;
    return k;
  }

  RegionKey RegionOf(double x, double y) const { return {IndexOf(x), IndexOf(y)}; }

 private:
  double Edge(int64_t k) const { return static_cast<double>(k) * side_; }

  double min_distance_;
  double side_;
};

}  // namespace scallop
