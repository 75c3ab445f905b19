// Rect: an axis-aligned rectangle, half-open [x0, x1) x [y0, y1).
// Half-open so that rectangles tiling the plane own every point exactly once.
#pragma once

#include <algorithm>

#include "scallop/geometry/vec2.h"

namespace scallop {

struct Rect {
  double x0 = 0.0;
  double y0 = 0.0;
  double x1 = 0.0;
  double y1 = 0.0;

  constexpr double Width() const { return x1 - x0; }
  constexpr double Height() const { return y1 - y0; }
  constexpr double Area() const { return Width() * Height(); }
  // True when x0 <= p.x < x1 and y0 <= p.y < y1.
  constexpr bool Contains(Vec2 p) const { return x0 <= p.x && p.x < x1 && y0 <= p.y && p.y < y1; }
  friend constexpr bool operator==(const Rect&, const Rect&) = default;
};

// Squared distance from p to the closed rectangle (0 inside it).
constexpr double SquaredDistance(const Rect& r, Vec2 p) {
  const double dx = std::max({r.x0 - p.x, 0.0, p.x - r.x1});
  const double dy = std::max({r.y0 - p.y, 0.0, p.y - r.y1});
  return dx * dx + dy * dy;
}

// The rectangle grown by `margin` on every side.
constexpr Rect Grown(const Rect& r, double margin) {
  return {r.x0 - margin, r.y0 - margin, r.x1 + margin, r.y1 + margin};
}

}  // namespace scallop
