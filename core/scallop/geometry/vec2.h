// Vec2: a point or displacement in the plane, in double precision.
// Plain value type shared by every part of the core.
#pragma once

#include <cmath>

#include "scallop/base/deterministic_math.h"

namespace scallop {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;

  friend constexpr Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
  friend constexpr Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
  friend constexpr Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
  friend constexpr bool operator==(Vec2 a, Vec2 b) = default;
};

constexpr double Dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
constexpr double Cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
constexpr double SquaredLength(Vec2 a) { return Dot(a, a); }
inline double Length(Vec2 a) { return std::hypot(a.x, a.y); }
constexpr double SquaredDistance(Vec2 a, Vec2 b) { return SquaredLength(a - b); }

// The unit vector at `angle` radians from the +x axis, from our own sin and
// cos so the bits do not depend on the CPU (base/deterministic_math.h).
inline Vec2 UnitAt(double angle) {
  Vec2 unit;
  DetSinCos(angle, &unit.y, &unit.x);
  return unit;
}

}  // namespace scallop
