// How a world cuts the plane into regions: square regions of side S = 16 d
// (a radius-field world: S = 6 r_max), region (i, j) owning
// [i S, (i+1) S) x [j S, (j+1) S), each with a rank that fixes which
// neighbours it depends on; and how many bits a point id gives the index in a
// region (point_id.h). See docs/design.md, "Regions" and "Field worlds on the
// plane".
#pragma once

#include <cmath>
#include <compare>
#include <cstdint>

#include "scallop/base/precision_range.h"
#include "scallop/geometry/rect.h"
#include "scallop/plane/world.h"

namespace scallop {

// Region side in units of d. 16 d holds about 220 A3 points and leaves room
// for the growth margin of region_generator.h: every point that constrains a
// region lies within its 8 neighbours.
inline constexpr double kRegionSideInD = 16.0;

// Regions -2^28 .. 2^28 - 1 on each axis tile exactly [-2^32 d, 2^32 d).
inline constexpr auto kRegionsPerHalfAxis =
    static_cast<int64_t>(kPrecisionRangeInD / kRegionSideInD);

// Region side of a radius-field world in units of r_max. A field world's
// points conflict up to r_max apart and its runs spill up to about 2 r_max,
// so regions must be a few r_max wide for every interaction to stay within 8
// neighbours and the sampling margin clear of the spill (region_generator.h);
// where the field is near r_min a region holds about 0.86 (6 r_max / r_min)^2
// points, 2,000 at r_max / r_min = 8 and 310,000 at 100, which is why the
// side is not 16 r_max (2.2 million at 100). docs/design.md has the argument.
inline constexpr double kFieldRegionSideInRMax = 6.0;

// Point-id index bits (point_id.h) of a constant world: 10.
inline constexpr int kConstantPointIdIndexBits = 10;

// Index bits a field world's ids need: enough for the most points a region
// of side `side_in_r_min` r_min can hold at spacing r_min. By Folkman and
// Graham's bound, points at least 1 apart in a convex set of area A and
// perimeter P number at most (2 / sqrt 3) A + P / 2 + 1; for the square,
// (2 / sqrt 3) a^2 + 2 a + 1. At least the constant worlds' 10.
constexpr int FieldPointIdIndexBits(double side_in_r_min) {
  const double most = 1.1547005383792517 * side_in_r_min * side_in_r_min + 2 * side_in_r_min + 1;
  int bits = kConstantPointIdIndexBits;
  while (static_cast<double>(uint64_t{1} << bits) <= most) ++bits;
  return bits;
}

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
  // A constant world's layout. REQUIRES: min_distance finite and > 0.
  explicit RegionLayout(double min_distance)
      : min_distance_(min_distance),
        side_(kRegionSideInD * min_distance),
        index_bits_(kConstantPointIdIndexBits),
        regions_per_half_axis_(kRegionsPerHalfAxis) {}

  // The world's layout: the constant one above, or for a field world side
  // 6 r_max, FieldPointIdIndexBits(6 r_max / r_min) index bits, and the
  // precision range 2^32 r_min (d is r_min).
  explicit RegionLayout(const World& world) : RegionLayout(world.min_distance()) {
    if (world.radius_field() == nullptr) return;
    side_ = kFieldRegionSideInRMax * world.max_spacing();
    index_bits_ = FieldPointIdIndexBits(side_ / min_distance_);
    regions_per_half_axis_ = static_cast<int64_t>(std::ceil(precision_limit() / side_));
  }

  double side() const { return side_; }
  double precision_limit() const { return kPrecisionRangeInD * min_distance_; }
  // Bits of a point id that hold the index in its region (point_id.h).
  int point_id_index_bits() const { return index_bits_; }
  // Regions -n .. n - 1 on each axis cover the precision range.
  int64_t regions_per_half_axis() const { return regions_per_half_axis_; }

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
  int index_bits_;
  int64_t regions_per_half_axis_;
};

}  // namespace scallop
