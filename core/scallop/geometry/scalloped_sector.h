// ScallopedSector: the points seen from an apex at angles in [angle_begin, angle_end] and
// distances between a near and a far RadialCurve (Dunbar & Humphreys 2006), with its closed-form
// area, the inverse of the cumulative area and uniform sampling.
#pragma once

#include "scallop/geometry/radial_curve.h"
#include "scallop/geometry/vec2.h"

namespace scallop {

struct ScallopedSector;

// What a sector's area function needs at its two ends, computed once (a region caches it per
// sector): the unit directions of the end angles and RadialCurve::HalfSquareIntegralRemainder of
// the near and far curves there. SectorEnds::Of computes it; a holder may instead keep values
// computed earlier by the very same calls, which are pure, so results stay bit-identical.
struct SectorEnds {
  Vec2 begin_direction;
  Vec2 end_direction;
  double near_begin = 0.0;  // near.HalfSquareIntegralRemainder(begin_direction)
  double near_end = 0.0;
  double far_begin = 0.0;
  double far_end = 0.0;

  // Up to four remainders (two atan). REQUIRES: directions = UnitAt of the sector's end angles
  // (to rounding; the sector's area is then defined by these directions).
  static SectorEnds Of(const ScallopedSector& sector, Vec2 begin_direction, Vec2 end_direction);
};

// Invariants (REQUIRES for every method): angle_begin < angle_end, both in [-pi, pi];
// 0 <= near(t) <= far(t) on the range; near and far do not cross inside it; each curve is defined
// on the whole range (arcs: rays meet the circle; lines: rho > 0). All points are apex-relative.
struct ScallopedSector {
  double angle_begin = 0.0;
  double angle_end = 0.0;
  RadialCurve near;
  RadialCurve far;

  // A(alpha) = integral over [angle_begin, alpha] of (far^2 - near^2) / 2, closed form from
  // RadialCurve::HalfSquareIntegral. O(1): four antiderivative evaluations. Absolute error a few
  // ulps of (scale^2 * angular width), scale the largest centre distance or radius involved.
  double AreaUpTo(double angle) const;
  // A(angle_end). Same cost and error as AreaUpTo.
  double Area() const { return AreaUpTo(angle_end); }

  // A^-1: the angle in [angle_begin, angle_end] whose AreaUpTo is `area` (clamped to
  // [0, Area()]). Safeguarded Newton (dA/dt = (far^2 - near^2) / 2) inside a bisection bracket,
  // iterated until the step or the bracket stops shrinking, so the result is as accurate as
  // AreaUpTo's rounding allows (typically ~1e-15 relative to the width). Usually 4-6 iterations,
  // capped at 200. REQUIRES: Area() > 0.
  double AngleAtArea(double area) const;
  // As AngleAtArea, given UnitAt(angle_begin) and UnitAt(angle_end) (to rounding), saving a sincos.
  double AngleAtArea(double area, Vec2 begin_direction, Vec2 end_direction) const;
  // As AngleAtArea, given the ends' data (bit-identical to the overload above with the same
  // directions), saving the four remainders at the ends.
  double AngleAtArea(double area, const SectorEnds& ends) const;

  // A uniformly distributed point of the sector (apex-relative) from u1, u2 in [0, 1):
  // theta = A^-1(u2 A), distance = sqrt(g^2 + u1 (h^2 - g^2)). Cost: one AngleAtArea.
  Vec2 Sample(double u1, double u2) const;
  // As Sample, given the unit directions of the end angles (as a region caches them).
  Vec2 Sample(double u1, double u2, Vec2 begin_direction, Vec2 end_direction) const;
  // As Sample, given the ends' data (bit-identical to the overload above with the same
  // directions): no remainder evaluations outside AngleAtArea's iterations.
  Vec2 Sample(double u1, double u2, const SectorEnds& ends) const;

  // True when `relative` lies in the closed sector. Cost: one atan2, two DistanceAlong.
  bool Contains(Vec2 relative) const;
  // As Contains, given the point's angle (from atan2), unit direction and distance, so a region
  // can share the atan2 among its sectors. Handles the angle pi = -pi seam.
  bool ContainsPolar(double angle, Vec2 direction, double distance) const;
};

// The area between `near` and `far` over the angles [t0, t1] with unit directions e0, e1:
// [F_far]_t0^t1 - [F_near]_t0^t1 through RadialCurve's split antiderivative (no gamma, no sincos).
// O(1): up to two atan. REQUIRES: the ScallopedSector invariants on [t0, t1].
inline double AreaBetween(const RadialCurve& near, const RadialCurve& far, double t0, Vec2 e0,
                          double t1, Vec2 e1) {
  return (far.LinearCoefficient() - near.LinearCoefficient()) * (t1 - t0) +
         ((far.HalfSquareIntegralRemainder(e1) - far.HalfSquareIntegralRemainder(e0)) -
          (near.HalfSquareIntegralRemainder(e1) - near.HalfSquareIntegralRemainder(e0)));
}

}  // namespace scallop
