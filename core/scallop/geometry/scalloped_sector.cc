// ScallopedSector: closed-form area, the inverse cumulative area by safeguarded Newton, and
// uniform sampling by inversion (Dunbar & Humphreys 2006, section "scalloped sectors").
#include "scallop/geometry/scalloped_sector.h"

#include <cmath>
#include <limits>
#include <numbers>

namespace scallop {

double ScallopedSector::AreaUpTo(double angle) const {
  const Vec2 begin = UnitAt(angle_begin);
  const Vec2 at = UnitAt(angle);
  return (far.HalfSquareIntegralAlong(angle, at) -
          far.HalfSquareIntegralAlong(angle_begin, begin)) -
         (near.HalfSquareIntegralAlong(angle, at) -
          near.HalfSquareIntegralAlong(angle_begin, begin));
}

double ScallopedSector::AngleAtArea(double area) const {
  const Vec2 begin = UnitAt(angle_begin);
  const Vec2 end = UnitAt(angle_end);
  const double far_base = far.HalfSquareIntegralAlong(angle_begin, begin);
  const double near_base = near.HalfSquareIntegralAlong(angle_begin, begin);
  const double total = (far.HalfSquareIntegralAlong(angle_end, end) - far_base) -
                       (near.HalfSquareIntegralAlong(angle_end, end) - near_base);
  if (!(area > 0.0)) return angle_begin;
  if (area >= total) return angle_end;
  double low = angle_begin;
  double high = angle_end;
  // Start from the angle a uniform density would give; Newton then corrects for the shape.
  double angle = angle_begin + (angle_end - angle_begin) * (area / total);
  const double epsilon = std::numeric_limits<double>::epsilon();
  for (int iteration = 0; iteration < 200; ++iteration) {
    const Vec2 direction = UnitAt(angle);
    const double residual = ((far.HalfSquareIntegralAlong(angle, direction) - far_base) -
                             (near.HalfSquareIntegralAlong(angle, direction) - near_base)) -
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
    if (std::fabs(next - angle) <= 4.0 * epsilon * std::fmax(1.0, std::fabs(angle))) return next;
    angle = next;
  }
  return angle;
}

Vec2 ScallopedSector::Sample(double u1, double u2) const {
  const double angle = AngleAtArea(u2 * Area());
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
  return ContainsPolar(std::atan2(relative.y, relative.x), (1.0 / distance) * relative, distance);
}

}  // namespace scallop
