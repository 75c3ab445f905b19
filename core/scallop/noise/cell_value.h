// The "cell value" channel of cellular noise: a number in [0, 1) fixed by a
// point's id alone, so every position whose nearest point is that point gets
// the same value, on every server and machine.
#pragma once

#include <cstdint>

#include "scallop/random/rng.h"

namespace scallop {

// The first output of SplitMix64 seeded with the id, as a double:
//   CellValue(id) = (Mix64(id + 0x9e3779b97f4a7c15) >> 11) * 2^-53,
// i.e. Rng(id).Uniform(). Uniform over the 2^53 multiples of 2^-53 in
// [0, 1); ids that differ in any bit give unrelated values. O(1), exact.
constexpr double CellValue(uint64_t id) { return Rng(id).Uniform(); }

}  // namespace scallop
