// Rect: an axis-aligned rectangle, half-open [x0, x1) x [y0, y1).
// Half-open so that rectangles tiling the plane own every point exactly once.
#pragma once

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

}  // namespace scallop
