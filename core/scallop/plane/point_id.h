// Point ids: a documented bit layout of (region, index in region), in the
// manner of S2 cell ids, so the same point always carries the same id.
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
// by a multiple of 2^27 in i or j, i.e. they lie at least 2^31 d apart. DecodePointId inverts the layout given any region within
// 2^26 regions (2^30 d) of the point, such as one the query touched.
#pragma once

#include <cstdint>

#include "scallop/plane/region_layout.h"

namespace scallop {

inline constexpr int kPointIdIndexBits = 10;
inline constexpr int kPointIdRegionBits = 27;

constexpr uint64_t EncodePointId(RegionKey region, uint32_t index) {
  constexpr uint64_t mask = (uint64_t{1} << kPointIdRegionBits) - 1;
  return ((static_cast<uint64_t>(region.i) & mask) << (kPointIdRegionBits + kPointIdIndexBits)) |
         ((static_cast<uint64_t>(region.j) & mask) << kPointIdIndexBits) |
         (index & ((1u << kPointIdIndexBits) - 1));
}

struct DecodedPointId {
  RegionKey region;
  uint32_t index;
};

// The (region, index) of `id` whose region is nearest `near` (within 2^26
// regions of it on each axis). O(1).
constexpr DecodedPointId DecodePointId(uint64_t id, RegionKey near) {
  constexpr int64_t modulus = int64_t{1} << kPointIdRegionBits;
  constexpr uint64_t mask = static_cast<uint64_t>(modulus - 1);
  auto unwrap = [&](uint64_t field, int64_t reference) {
    // The k = field (mod 2^27) closest to reference.
    int64_t delta = (static_cast<int64_t>(field) - (reference & (modulus - 1))) & (modulus - 1);
    if (delta >= modulus / 2) delta -= modulus;
    return reference + delta;
  };
  return {{unwrap((id >> (kPointIdRegionBits + kPointIdIndexBits)) & mask, near.i),
           unwrap((id >> kPointIdIndexBits) & mask, near.j)},
          static_cast<uint32_t>(id & ((1u << kPointIdIndexBits) - 1))};
}

}  // namespace scallop
