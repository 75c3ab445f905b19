// ScallopedSector: closed-form area, the inverse cumulative area by safeguarded Newton, and
// uniform sampling by inversion (Dunbar & Humphreys 2006, section "scalloped sectors").
#include "scallop/geometry/scalloped_sector.h"
#include "scallop/base/deterministic_math.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace scallop {

double ScallopedSector::AreaUpTo(double angle) const {
  return AreaBetween(near, far, angle_begin, UnitAt(angle_begin), angle, UnitAt(angle));
}

double ScallopedSector::AngleAtArea(double area) const {
  return AngleAtArea(area, UnitAt(angle_begin), UnitAt(angle_end));
}

SectorEnds SectorEnds::Of(const ScallopedSector& sector, Vec2 begin_direction, Vec2 end_direction) {
  SectorEnds ends;
  ends.begin_direction = begin_direction;
  ends.end_direction = end_direction;
  ends.near_begin = sector.near.HalfSquareIntegralRemainder(begin_direction);
  ends.near_end = sector.near.HalfSquareIntegralRemainder(end_direction);
  ends.far_begin = sector.far.HalfSquareIntegralRemainder(begin_direction);
  ends.far_end = sector.far.HalfSquareIntegralRemainder(end_direction);
  return ends;
}

double ScallopedSector::AngleAtArea(double area, Vec2 begin, Vec2 end) const {
  return AngleAtArea(area, SectorEnds::Of(*this, begin, end));
}

double ScallopedSector::AngleAtArea(double area, const SectorEnds& ends) const {
  // A(t) = slope_base * (t - angle_begin) + (R_far(t) - far_base) - (R_near(t) - near_base), the
  // split antiderivative of RadialCurve, so each iteration costs one sincos and up to two atan.
  const double linear = far.LinearCoefficient() - near.LinearCoefficient();
  const double far_base = ends.far_begin;
  const double near_base = ends.near_begin;
  const double total = linear * (angle_end - angle_begin) +
                       ((ends.far_end - far_base) - (ends.near_end - near_base));
  if (!(area > 0.0)) return angle_begin;
  if (area >= total) return angle_end;
  double low = angle_begin;
  double high = angle_end;
  // Start from the angle a uniform density would give; Newton then corrects for the shape.
  double angle = angle_begin + (angle_end - angle_begin) * (area / total);
  const double epsilon = std::numeric_limits<double>::epsilon();
  for (int iteration = 0; iteration < 200; ++iteration) {
    const Vec2 direction = UnitAt(angle);
    const double residual = (linear * (angle - angle_begin) +
                             ((far.HalfSquareIntegralRemainder(direction) - far_base) -
                              (near.HalfSquareIntegralRemainder(direction) - near_base))) -
                            area;
    if (residual == 0.0) return angle;
    if (residual < 0.0) {
      low = angle;
    } else {
      high = angle;
    }
    const double g = near.DistanceAlong(direction);
    const double h = far.DistanceAlong(direction);
    const double slope = 0.5 * (h * h - g * g);
    double next = slope > 0.0 ? angle - residual / slope : low - 1.0;  // force bisection
    if (!(next > low && next < high)) next = low + 0.5 * (high - low);
    // The bracket cannot shrink further, or Newton's step has fallen to rounding noise.
    if (!(next > low && next < high)) return angle;
    // std::max gives std::fmax's value here (for a NaN angle both give 1) without a libm call.
    if (std::fabs(next - angle) <= 4.0 * epsilon * std::max(1.0, std::fabs(angle))) return next;
    angle = next;
  }
  return angle;
}

Vec2 ScallopedSector::Sample(double u1, double u2) const {
  return Sample(u1, u2, UnitAt(angle_begin), UnitAt(angle_end));
}

Vec2 ScallopedSector::Sample(double u1, double u2, Vec2 begin_direction, Vec2 end_direction) const {
  return Sample(u1, u2, SectorEnds::Of(*this, begin_direction, end_direction));
}

Vec2 ScallopedSector::Sample(double u1, double u2, const SectorEnds& ends) const {
  // AreaBetween's expression, with its remainders taken from `ends`.
  const double total =
      (far.LinearCoefficient() - near.LinearCoefficient()) * (angle_end - angle_begin) +
      ((ends.far_end - ends.far_begin) - (ends.near_end - ends.near_begin));
  const double angle = AngleAtArea(u2 * total, ends);
  const Vec2 direction = UnitAt(angle);
  const double g = near.DistanceAlong(direction);
  const double h = far.DistanceAlong(direction);
  const double squared = g * g + u1 * (h * h - g * g);
  return std::sqrt(squared > 0.0 ? squared : 0.0) * direction;
}

bool ScallopedSector::ContainsPolar(double angle, Vec2 direction, double distance) const {
  if (angle < angle_begin || angle > angle_end) {
    // atan2 gives pi for rays along -x with y = +0; a sector may start at -pi instead.
    if (!(angle == std::numbers::pi && angle_begin == -std::numbers::pi)) return false;
  }
  return distance >= near.DistanceAlong(direction) && distance <= far.DistanceAlong(direction);
}

bool ScallopedSector::Contains(Vec2 relative) const {
  const double distance = Length(relative);
  if (distance == 0.0) return near.DistanceAt(angle_begin) <= 0.0;
  return ContainsPolar(DetAtan2(relative.y, relative.x), (1.0 / distance) * relative, distance);
}

}  // namespace scallop
