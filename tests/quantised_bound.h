// The stated error bound of a quantised coordinate (docs/wire.md), for the
// tests of the compact encodings: half a cell of S / 2^16, plus the rounding
// of the decoding sum edge + (c + 0.5) q, at most ulp(coordinate) + ulp(S).
#pragma once

#include <cmath>
#include <limits>

namespace scallop {

// The gap from |v| to the next double up: ulp(v) as the bound means it.
inline double UlpAbove(double v) {
  v = std::fabs(v);
  return std::nextafter(v, std::numeric_limits<double>::infinity()) - v;
}

inline double QuantisedBound(double coordinate, double region_side) {
  return std::ldexp(region_side, -17) + UlpAbove(coordinate) + UlpAbove(region_side);
}

}  // namespace scallop
