// A position's x and y as one vector of two doubles (an SSE2 register on
// x86-64), for the per-position arithmetic of the nearest lookups: each lane
// performs the scalar operations, so the results have the scalar bits.
#pragma once

#include <cstdint>
#include <cstring>

#include "scallop/geometry/double_lanes.h"
#include "scallop/geometry/vec2.h"

namespace scallop {

using Pair = Doubles;
using PairBits = DoubleBits;                                // a comparison's lanes
using PairCells = int32_t __attribute__((vector_size(8)));  // truncated to int
static_assert(sizeof(Pair) == sizeof(Vec2));

[[gnu::always_inline]] inline Pair Broadcast2(double value) { return Pair{value, value}; }

[[gnu::always_inline]] inline Pair LoadPair(const Vec2& p) {
  Pair pair;
  std::memcpy(&pair, &p, sizeof(pair));
  return pair;
}

// Bit k set: lane k of a comparison holds true. GCC 12 tests the lanes one
// by one in six instructions where SSE2 has one; and where the masks of
// several comparisons are and-ed first, it normalizes them lane by lane
// before that one, so combine the bits instead.
[[gnu::always_inline]] inline unsigned LanesSet(PairBits mask) {
#if defined(__SSE2__)
  return static_cast<unsigned>(__builtin_ia32_movmskpd(reinterpret_cast<Pair>(mask)));
#else
  return (mask[0] != 0 ? 1u : 0u) | (mask[1] != 0 ? 2u : 0u);
#endif
}

[[gnu::always_inline]] inline bool BothLanes(PairBits mask) { return LanesSet(mask) == 3; }

// |p| lane by lane (the sign bit cleared).
[[gnu::always_inline]] inline Pair Magnitude(Pair p) {
  return reinterpret_cast<Pair>(reinterpret_cast<PairBits>(p) & ~(PairBits{1, 1} << 63));
}

}  // namespace scallop
