// RadialCurve: construction and the closed-form area antiderivative.
// Kept apart from the header so the hot DistanceAlong stays inline while the
// transcendental pieces live here.
#include "scallop/geometry/radial_curve.h"
#include "scallop/base/deterministic_math.h"

#include <cmath>

namespace scallop {

RadialCurve RadialCurve::Arc(Vec2 centre, double radius, int sign) {
  RadialCurve curve;
  curve.kind_ = Kind::kArc;
  curve.vector_ = centre;
  curve.scalar_ = radius;
  curve.sign_ = static_cast<int8_t>(sign < 0 ? -1 : 1);
  return curve;
}

RadialCurve RadialCurve::Line(Vec2 unit_normal, double offset) {
  RadialCurve curve;
  curve.kind_ = Kind::kLine;
  if (offset < 0.0) {
    unit_normal = -1.0 * unit_normal;
    offset = -offset;
  }
  curve.vector_ = unit_normal;
  curve.scalar_ = offset;
  return curve;
}

double RadialCurve::HalfSquareIntegralAlong(double angle, Vec2 direction) const {
  if (kind_ == Kind::kLine) return HalfSquareIntegralRemainder(direction);
  // atan2(0, 0) = 0: for a circle centred on the apex gamma is arbitrary and cancels.
  const double polar_angle = DetAtan2(vector_.y, vector_.x);
  return LinearCoefficient() * (angle - polar_angle) + HalfSquareIntegralRemainder(direction);
}

double RadialCurve::HalfSquareIntegralRemainder(Vec2 direction) const {
  if (kind_ == Kind::kLine) {
    // tan(t - phi) = sin / cos of the angle between the normal and the ray.
    return 0.5 * scalar_ * scalar_ * Cross(vector_, direction) / Dot(vector_, direction);
  }
  const double radius_squared = scalar_ * scalar_;
  const double along = Dot(vector_, direction);     // d cos u
  const double across = Cross(vector_, direction);  // w = d sin u
  // (d^2 / 2) sin 2u = (d cos u)(d sin u).
  double remainder = along * across;
  if (scalar_ > 0.0 && across != 0.0) {
    // w sqrt(R^2 - w^2) + R^2 asin(w / R) written as w S + R^2 atan(w / S) with S = sqrt((R - w)
    // (R + w)): near the tangent rays (|w| -> R) asin and R^2 - w^2 each lose half the digits,
    // while this form is well conditioned in both w and S (its partial derivatives vanish there).
    // w == 0 (always, for a circle centred on the apex) contributes nothing: skip the atan.
    double w = across;
    if (w > scalar_) w = scalar_;  // rounding can push |w| a hair past R at tangent rays
    if (w < -scalar_) w = -scalar_;
    const double root = std::sqrt((scalar_ - w) * (scalar_ + w));
    // atan(w / S) equals atan2(w, S) for S >= 0 (S = 0 gives +-inf -> +-pi/2) and is cheaper;
    // the division's rounding moves the result by at most half an ulp of pi/2.
    remainder += sign_ * (w * root + radius_squared * DetAtan(w / root));
  }
  return 0.5 * remainder;
}

}  // namespace scallop
