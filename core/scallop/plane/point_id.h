// Point ids: a documented bit layout of (region, index in region), in the
// manner of S2 cell ids, so the same point always carries the same id.
//
// A constant world (10 index bits, 27 region bits):
//
//   bit 63 ............ 37 | 36 ............ 10 | 9 ...... 0
//       i mod 2^27 (27 b)  |  j mod 2^27 (27 b)  |  k (10 b)
//
// (i, j) is the region whose rectangle holds the point, k its position in
// that region's list: first the points its lower-ranked neighbours placed
// there, then its own in generation order (region_generator.h). k < 1024: a
// 16 d region holds at most 296 points, the hexagonal packing bound. The
// plane's precision range holds about 2^66 points, more than 64 bits can
// name, so ids wrap: two points have equal ids only if their regions differ
// by a multiple of 2^27 in i or j, i.e. they lie at least 2^31 d apart. DecodePointId inverts the
// layout given any region within 2^26 regions (2^30 d) of the point, such as one the query touched.
//
// A radius-field world (regions of side S = 6 r_max) needs a wider index: b =
// FieldPointIdIndexBits(S / r_min) bits (region_layout.h: the Folkman-Graham
// packing bound of a square at spacing r_min; 10 bits up to r_max / r_min = 4,
// 12 at 8, 14 at 16, 19 at 100), and each region field gets g = (64 - b) / 2
// bits (22 at ratio 100):
//
//   bits 63 .. b+g | b+g-1 .. b | b-1 .. 0
//   i mod 2^g      | j mod 2^g  | k
//
// Ids then wrap at 2^g regions, 2^g S apart (at least 2^30.9 r_min, at ratio
// 5; 2^22 * 600 r_min = 2^31.2 r_min at ratio 100: within the precision range
// of 2^32 r_min each way, as 2^31 d is for a constant world), and
// DecodePointId needs a region within 2^(g-1) regions of the point. The
// layout a world uses is RegionLayout(world).point_id_index_bits().
#pragma once

#include <cstdint>

#include "scallop/plane/region_layout.h"

namespace scallop {

// A constant world's layout.
inline constexpr int kPointIdIndexBits = kConstantPointIdIndexBits;
inline constexpr int kPointIdRegionBits = 27;

// Bits of each region field when `index_bits` hold the index.
constexpr int PointIdRegionBits(int index_bits) { return (64 - index_bits) / 2; }

// REQUIRES: index < 2^index_bits; index_bits in [10, 24].
constexpr uint64_t EncodePointId(RegionKey region, uint32_t index,
                                 int index_bits = kPointIdIndexBits) {
  const int region_bits = PointIdRegionBits(index_bits);
  const uint64_t mask = (uint64_t{1} << region_bits) - 1;
  return ((static_cast<uint64_t>(region.i) & mask) << (region_bits + index_bits)) |
         ((static_cast<uint64_t>(region.j) & mask) << index_bits) |
         (index & ((uint64_t{1} << index_bits) - 1));
}

struct DecodedPointId {
  RegionKey region;
  uint32_t index;
};

// The (region, index) of `id` whose region is nearest `near` (within
// 2^(g-1) regions of it on each axis; 2^26 for a constant world). O(1).
constexpr DecodedPointId DecodePointId(uint64_t id, RegionKey near,
                                       int index_bits = kPointIdIndexBits) {
  const int region_bits = PointIdRegionBits(index_bits);
  const int64_t modulus = int64_t{1} << region_bits;
  const uint64_t mask = static_cast<uint64_t>(modulus - 1);
  auto unwrap = [&](uint64_t field, int64_t reference) {
    // The k = field (mod 2^g) closest to reference.
    int64_t delta = (static_cast<int64_t>(field) - (reference & (modulus - 1))) & (modulus - 1);
    if (delta >= modulus / 2) delta -= modulus;
    return reference + delta;
  };
  return {{unwrap((id >> (region_bits + index_bits)) & mask, near.i),
           unwrap((id >> index_bits) & mask, near.j)},
          static_cast<uint32_t>(id & ((uint64_t{1} << index_bits) - 1))};
}

}  // namespace scallop
