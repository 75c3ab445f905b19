// RadialCurve: a boundary of a scalloped sector, seen from the sector's apex as a
// distance rho(t) along the ray at angle t. Either an arc of a circle (Dunbar &
// Humphreys 2006) or a straight line, which clips neighbourhoods to rectangles.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

#include "scallop/geometry/vec2.h"

namespace scallop {

class RadialCurve {
 public:
  enum class Kind : uint8_t { kArc, kLine };

  // The half of the circle |x - centre| = radius met along rays from the apex (the origin of
  // `centre`): sign +1 the farther crossing, -1 the nearer one, so that
  //   rho(t) = d cos(t - gamma) + sign * sqrt(radius^2 - (d sin(t - gamma))^2)
  // with (d, gamma) the polar coordinates of `centre`. A circle centred on the apex is an arc with
  // sign +1 and rho = radius. O(1), no trigonometry (the polar angle gamma is never stored: it
  // only shifts the antiderivative by a constant, see HalfSquareIntegralRemainder).
  // REQUIRES: radius >= 0, sign in {-1, +1}, finite inputs.
  static RadialCurve Arc(Vec2 centre, double radius, int sign);

  // The line {x : Dot(unit_normal, x) = offset}, x relative to the apex:
  //   rho(t) = offset / cos(t - phi), phi the angle of unit_normal,
  // meaningful where positive. Stored normalised to offset >= 0 (negating both when offset < 0
  // describes the same line), so equal lines compare equal. O(1), no trigonometry.
  // REQUIRES: |unit_normal| = 1 to rounding, finite inputs.
  static RadialCurve Line(Vec2 unit_normal, double offset);

  // The other half of the same circle (sign negated), without recomputing its polar form. O(1).
  // REQUIRES: is_arc().
  RadialCurve OppositeHalf() const {
    RadialCurve curve = *this;
    curve.sign_ = static_cast<int8_t>(-sign_);
    return curve;
  }

  Kind kind() const { return kind_; }
  bool is_arc() const { return kind_ == Kind::kArc; }
  // Arc: the circle's centre (apex-relative) and radius; sign in {-1, +1}.
  Vec2 centre() const { return vector_; }
  double radius() const { return scalar_; }
  int sign() const { return sign_; }
  // Line: the normalised unit normal and offset >= 0.
  Vec2 normal() const { return vector_; }
  double offset() const { return scalar_; }

  // rho along the ray at `angle`. O(1): one sincos and one sqrt (or a division).
  // Off the arc's angular range (rays that miss the circle) the square root is clamped at 0;
  // on rays parallel to a line the result is +-inf. Error: a few ulps of max(d, radius) for
  // arcs, away from tangent rays where the square root amplifies rounding.
  double DistanceAt(double angle) const { return DistanceAlong(UnitAt(angle)); }

  // rho along the ray with unit direction `direction`; as DistanceAt but no trigonometry.
  double DistanceAlong(Vec2 direction) const {
    if (kind_ == Kind::kLine) return scalar_ / Dot(vector_, direction);
    const double along = Dot(vector_, direction);
    const double across = Cross(vector_, direction);  // = d sin(t - gamma)
    // (R - w)(R + w) rather than R^2 - w^2: no cancellation near the tangent rays.
    const double discriminant = (scalar_ - across) * (scalar_ + across);
    return along + sign_ * std::sqrt(discriminant > 0.0 ? discriminant : 0.0);
  }

  // Closed-form antiderivative of DistanceAt(t)^2 / 2, so the area of a sector over [a, b] is
  // [F_far]_a^b - [F_near]_a^b. With u = t - gamma, w = d sin u:
  //   Arc:  F = (R^2 u + (d^2 / 2) sin 2u + sign (w sqrt(R^2 - w^2) + R^2 asin(w / R))) / 2
  //   Line: F = (c^2 / 2) tan(t - phi)
  // Continuous on any angular range where the curve is defined (arc: |w| <= R; line: cos != 0).
  // Cost: one sincos, one sqrt and one atan (arc) or one sincos (line). Absolute error a few ulps
  // of max(d, R)^2 * (1 + |u|) for arcs, also at the tangent rays (evaluated in a form that stays
  // well conditioned there); differences of nearby values lose relative accuracy.
  double HalfSquareIntegral(double angle) const {
    return HalfSquareIntegralAlong(angle, UnitAt(angle));
  }
  // As HalfSquareIntegral, given also direction = UnitAt(angle) (to rounding), which callers often
  // have already: then no sin/cos is needed (sin u, cos u come from dot and cross products), only
  // one atan for arcs not centred on the apex (plus one atan2 for gamma, which area differences
  // avoid through the split below). REQUIRES: |direction| = 1, its angle == angle.
  double HalfSquareIntegralAlong(double angle, Vec2 direction) const;

  // The antiderivative split as F(t) = LinearCoefficient() * (t - gamma) + Remainder(direction):
  // arc: coefficient R^2 / 2, remainder ((d^2 / 2) sin 2u + sign (w S + R^2 atan(w / S))) / 2;
  // line: coefficient 0, remainder (c^2 / 2) tan(t - phi). Differences F(t1) - F(t0) then need
  // no gamma: LinearCoefficient() * (t1 - t0) + Remainder(e1) - Remainder(e0). The remainder
  // costs one sqrt and one atan (arcs not centred on the apex), a division (lines).
  // REQUIRES: |direction| = 1.
  double LinearCoefficient() const { return kind_ == Kind::kLine ? 0.0 : 0.5 * scalar_ * scalar_; }
  double HalfSquareIntegralRemainder(Vec2 direction) const;

  // Bounds on rho over any ray where the curve is defined: MinDistance() <= rho <= MaxDistance().
  // Arc: |d - R| and d + R; line: offset and +inf. O(1), one sqrt for arcs.
  double MinDistance() const {
    if (kind_ == Kind::kLine) return scalar_;
    return std::fabs(std::sqrt(SquaredLength(vector_)) - scalar_);
  }
  double MaxDistance() const {
    if (kind_ == Kind::kLine) return std::numeric_limits<double>::infinity();
    return std::sqrt(SquaredLength(vector_)) + scalar_;
  }

  friend bool operator==(const RadialCurve& a, const RadialCurve& b) {
    return a.kind_ == b.kind_ && a.sign_ == b.sign_ && a.vector_ == b.vector_ &&
           a.scalar_ == b.scalar_;
  }

 private:
  // 32 bytes: regions hold two curves per sector and A1 keeps one region per frontier point.
  Vec2 vector_;          // arc: centre; line: unit normal
  double scalar_ = 0.0;  // arc: radius; line: offset >= 0
  Kind kind_ = Kind::kArc;
  int8_t sign_ = 1;
};

// The cases of CurveCrossings, below.
namespace radial_curve_internal {

inline Vec2 Perpendicular(Vec2 v) { return {-v.y, v.x}; }

inline int CircleCircle(Vec2 c1, double r1, Vec2 c2, double r2, Vec2 points[2]) {
  const Vec2 delta = c2 - c1;
  const double distance_squared = SquaredLength(delta);
  if (distance_squared == 0.0) return 0;
  const double distance = std::sqrt(distance_squared);
  const double along = (r1 * r1 - r2 * r2 + distance_squared) / (2.0 * distance);
  const double half_chord_squared = r1 * r1 - along * along;
  if (!(half_chord_squared > 0.0)) return 0;
  const Vec2 unit = (1.0 / distance) * delta;
  const Vec2 base = c1 + along * unit;
  const Vec2 offset = std::sqrt(half_chord_squared) * Perpendicular(unit);
  points[0] = base - offset;
  points[1] = base + offset;
  return 2;
}

inline int CircleLine(Vec2 centre, double radius, Vec2 normal, double offset, Vec2 points[2]) {
  const double signed_distance = Dot(normal, centre) - offset;
  const double half_chord_squared = radius * radius - signed_distance * signed_distance;
  if (!(half_chord_squared > 0.0)) return 0;
  const Vec2 foot = centre - signed_distance * normal;
  const Vec2 along = std::sqrt(half_chord_squared) * Perpendicular(normal);
  points[0] = foot - along;
  points[1] = foot + along;
  return 2;
}

inline int LineLine(Vec2 n1, double c1, Vec2 n2, double c2, Vec2 points[2]) {
  const double determinant = Cross(n1, n2);
  if (determinant == 0.0) return 0;
  points[0] = {(c1 * n2.y - c2 * n1.y) / determinant, (n1.x * c2 - n2.x * c1) / determinant};
  return 1;
}

}  // namespace radial_curve_internal

// Points (apex-relative) where the full circles / lines underlying `a` and `b` cross, ignoring
// which half of a circle each arc uses. Writes up to two points to `points` and returns how many.
// Tangent, coincident, concentric and parallel pairs give 0: touching curves need no split.
// O(1), one sqrt. Error: a few ulps of the operands' scale, more near tangency. Inline: A1 calls
// it twice for every sector a disk reaches (about 1% of its instructions went to the calls).
inline int CurveCrossings(const RadialCurve& a, const RadialCurve& b, Vec2 points[2]) {
  using namespace radial_curve_internal;
  if (a.is_arc() && b.is_arc()) {
    return CircleCircle(a.centre(), a.radius(), b.centre(), b.radius(), points);
  }
  if (a.is_arc()) return CircleLine(a.centre(), a.radius(), b.normal(), b.offset(), points);
  if (b.is_arc()) return CircleLine(b.centre(), b.radius(), a.normal(), a.offset(), points);
  return LineLine(a.normal(), a.offset(), b.normal(), b.offset(), points);
}

}  // namespace scallop
