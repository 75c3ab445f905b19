// The scales at which Scallop keeps its guarantees: how small or large d may
// be, and how far from the origin, in units of d, coordinates may go. One
// place for the bounded samplers, the infinite plane and the API alike.
#pragma once

namespace scallop {

// The minimum distances every part of Scallop supports: squares of
// coordinates up to 2^40 d and differences down to 2^-60 d stay finite and
// normal doubles, so the spacing tests mean what they say.
inline constexpr double kSmallestMinDistance = 0x1.0p-256;
inline constexpr double kLargestMinDistance = 0x1.0p256;

// Coordinates up to 2^32 d keep their rounding far below the spacing margin
// of sampling/spacing.h (8 ulp(2^32 d) = 2^-17 d), and region indices of
// plane/region_layout.h stay exact in doubles. Beyond it: OUT_OF_RANGE.
inline constexpr double kPrecisionRangeInD = 0x1.0p32;

}  // namespace scallop
