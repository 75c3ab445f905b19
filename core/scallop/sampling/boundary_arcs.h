// The arcs of a candidate's circle (radius s) that A3 removes: those its
// neighbours' disks cover, and those of the points it places. Only IEEE
// arithmetic and square roots, in a written order, so the keys' bits are
// the same everywhere.
#pragma once

#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "scallop/geometry/vec2.h"
#include "scallop/sampling/available_boundary.h"

namespace scallop {

// {sqrt(t[0]), sqrt(t[1])}: one packed square root where SSE2 has it (the
// same correctly rounded bits), where std::sqrt gave two, each behind a
// branch that keeps errno for negative inputs (t >= 0 here).
inline Doubles SquareRoots(Doubles t) {
#if defined(__SSE2__)
  return _mm_sqrt_pd(t);
#else
  return Doubles{std::sqrt(t[0]), std::sqrt(t[1])};
#endif
}

// The arcs that the neighbours at offset0 and offset1 from the candidate
// cover, into arcs[0] and arcs[1]. Each is centred on the direction
// o = offset, with ends along o -+ k o', k = sqrt(4 s^2 / D^2 - 1). Both at
// once, in the two lanes of SSE2 registers: the divisions and square roots
// are most of A3's arithmetic.
inline void CoveredArcs(Vec2 offset0, Vec2 offset1, double spacing_squared, KeyArc* arcs) {
  const Doubles x = {offset0.x, offset1.x}, y = {offset0.y, offset1.y};
  const Doubles four_s2 = {4 * spacing_squared, 4 * spacing_squared};
  const Doubles t = four_s2 / (x * x + y * y) - 1.0;
  const Doubles k = SquareRoots(t);
  // o' = (-y, x); from = o - k o', to = o + k o'.
  const Doubles from_key = PseudoAngles(x + k * y, y - k * x);
  const Doubles to_key = PseudoAngles(x - k * y, y + k * x);
  for (int lane = 0; lane < 2; ++lane) arcs[lane] = {from_key[lane], to_key[lane]};
}

// The arc of the candidate's circle that a point placed on it, in direction
// `direction` (any length), covers with its disk: half-width pi/3 about it.
// Rotating by -+60 degrees needs no trigonometry: cos = 1/2, sin = sqrt(3)/2.
inline KeyArc PlacedArc(Vec2 direction) {
  constexpr double kSin60 = 0.86602540378443864676372317075294;
  const Vec2 half = 0.5 * direction, turned = {-kSin60 * direction.y, kSin60 * direction.x};
  const Doubles keys = PseudoAngles(Doubles{half.x - turned.x, half.x + turned.x},
                                    Doubles{half.y - turned.y, half.y + turned.y});
  return {keys[0], keys[1]};
}

}  // namespace scallop
