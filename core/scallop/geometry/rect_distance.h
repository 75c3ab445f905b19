// SquaredDistance(Rect, Vec2) without a branch, for the loops that measure every point of a
// region against a rectangle: the gathering of a region's neighbours' points, and A3's count
// of candidates near its stop rectangle.
#pragma once

#include "scallop/geometry/rect.h"
#include "scallop/geometry/vec2.h"

namespace scallop {

// SquaredDistance(r, p), bit for bit, with both axes in the lanes of one SSE2 register (a GCC
// and Clang vector extension): along each, the larger of r.x0 - p.x and p.x - r.x1, or 0 when
// both are below it, as SquaredDistance takes the largest of the three (which of two equal
// values is taken, +0 or -0, does not change its square), then the same sum of squares.
// SquaredDistance's std::max of three, out of line in GCC's code, cost 2% of a cold plane
// query. O(1).
inline double SquaredDistanceInLanes(const Rect& r, Vec2 p) {
  using Doubles = double __attribute__((vector_size(16)));
  const Doubles v = {p.x, p.y};
  const Doubles below = Doubles{r.x0, r.y0} - v, above = v - Doubles{r.x1, r.y1};
  const Doubles zero = {0.0, 0.0};
  Doubles distance = below > above ? below : above;
  distance = distance > zero ? distance : zero;
  const Doubles squares = distance * distance;
  return squares[0] + squares[1];
}

}  // namespace scallop
