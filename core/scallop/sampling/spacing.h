// The spacing samplers actually keep between points: a hair above d.
//
// The contract is judged on returned doubles: dx^2 + dy^2 >= d^2. Points are
// placed on circles of radius `spacing` around earlier points, and rounding a
// coordinate of magnitude M moves it by up to ulp(M) / 2. A margin of at least
// 8 ulp(M) (and never below d * 2^-32) keeps every pair at least d apart after
// rounding, while the set stays maximal for `spacing`: no spot is farther than
// `spacing` from every point (see docs/design.md, "Rounding").
#pragma once

#include <algorithm>
#include <cmath>

namespace scallop {

// REQUIRES: min_distance > 0, max_abs_coordinate >= 0, both finite.
inline double SpacingFor(double min_distance, double max_abs_coordinate) {
  const double ulp = std::nextafter(max_abs_coordinate, INFINITY) - max_abs_coordinate;
  return min_distance + std::max(min_distance * 0x1.0p-32, 8.0 * ulp);
}

}  // namespace scallop
