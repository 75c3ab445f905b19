// The arcs of a candidate's circle (radius s) that A3 removes: those its
// neighbours' disks cover, and those of the points it places. Only IEEE
// arithmetic and square roots, in a written order, so the keys' bits are
// the same everywhere.
#pragma once

#include <cmath>

#include "scallop/geometry/double_lanes.h"
#include "scallop/geometry/vec2.h"
#include "scallop/sampling/available_boundary.h"

namespace scallop {

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

// How much of a circle a disk covers.
enum class DiskCover { kNone, kArc, kWhole };

// The arc of the circle of radius `radius` about a centre that the closed disk of radius
// `disk_radius` about the point at `offset` from that centre covers: the second intersection
// rule, for a disk of another radius than the circle's (an exclusion disk of a layered world, or
// a point's disk seen from an exclusion disk's circle). CoveredArcs is the case of equal radii.
// With L = |offset|, a = radius^2 + L^2 - disk_radius^2 and h = sqrt(4 radius^2 L^2 - a^2), the
// arc's ends lie along a o -+ h o' (o' = o turned left): the law of cosines, cos = a / (2 radius
// L), without dividing by it. kNone (arc untouched) when the circles do not cross: the disk lies
// beyond the circle or inside it; kWhole when the disk holds the circle. Only IEEE arithmetic
// and one square root; near tangency the ends move by about 1e-8 radians of rounding, where the
// circle runs within 1e-16 of the disk's edge, far inside the samplers' spacing margin.
inline DiskCover CoveredArcOfCircle(Vec2 offset, double radius, double disk_radius, KeyArc& arc) {
  const double l2 = SquaredLength(offset);
  const double sum = radius + disk_radius, difference = disk_radius - radius;
  if (l2 >= sum * sum) return DiskCover::kNone;
  if (l2 <= difference * difference) return difference >= 0 ? DiskCover::kWhole : DiskCover::kNone;
  const double r2 = radius * radius;
  const double a = r2 + l2 - disk_radius * disk_radius;
  const double h = std::sqrt(std::max(0.0, 4 * r2 * l2 - a * a));
  const Doubles keys =
      PseudoAngles(Doubles{a * offset.x + h * offset.y, a * offset.x - h * offset.y},
                   Doubles{a * offset.y - h * offset.x, a * offset.y + h * offset.x});
  arc = {keys[0], keys[1]};
  return DiskCover::kArc;
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
