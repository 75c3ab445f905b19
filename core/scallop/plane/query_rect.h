// The one rule for a rectangle query of the infinite plane, and the regions it
// reads. The engine, the viewport tracker, the server's calls and the CLI all
// check rectangles here, with their own limits and field names passed in.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "scallop/base/status.h"
#include "scallop/geometry/rect.h"
#include "scallop/plane/region_layout.h"
#include "scallop/plane/world.h"

namespace scallop {

// The regions low..high (inclusive on both axes) a half-open rectangle
// overlaps: the rectangle ends just below x1 and y1, so a rectangle whose x1
// sits on a seam does not reach the region beyond it.
struct RegionRange {
  RegionKey low;
  RegionKey high;

  // As a double: a rectangle may cross more regions than int64 can count.
  double Count() const {
    return (static_cast<double>(high.i - low.i) + 1) * (static_cast<double>(high.j - low.j) + 1);
  }
  bool Contains(RegionKey key) const {
    return low.i <= key.i && key.i <= high.i && low.j <= key.j && key.j <= high.j;
  }
};

// REQUIRES: rect finite with x0 < x1 and y0 < y1 (CheckQueryRect ok, or the
// cost check's rectangle). Exact: ownership agrees with RegionRect to the bit.
RegionRange RegionsOverlapping(const RegionLayout& layout, const Rect& rect);

// How messages name a world's regions: "16 min_distance" for a constant
// world, "6 r_max (r_max = 2.5)" for a radius-field world, whose regions
// scale with r_max (region_layout.h).
std::string RegionSideText(const World& world);

// The limits one kind of query enforces.
struct QueryLimit {
  // Largest area, in units of d^2.
  double max_area = 1e8;
  // The setting that holds max_area, named in messages ("max_query_area").
  std::string_view name = "max_query_area";
};

// The most regions a query under `max_area` may cross: max_area / 64 + 16.
// A square of the largest area crosses fewer (at most (sqrt(A)/16 + 1)^2 <=
// A/64 + 16 for every A), so only thin rectangles meet it, which would
// otherwise cost a region each at almost no area.
double MaxRegionsCrossed(double max_area);

// The whole rule for a rectangle of `world`, named `field` in messages
// ("rect", "viewport"): CheckRectBounds, then CheckQueryCost. O(1).
Status CheckQueryRect(const World& world, const Rect& rect, const QueryLimit& limit,
                      std::string_view field = "rect");

// The bounds half of the rule:
//   INVALID_ARGUMENT  a corner not finite ("rect.x0: must be finite"),
//                     x0 >= x1 or y0 >= y1 ("rect: x0 must be less than x1");
//   OUT_OF_RANGE      a corner beyond 2^32 d ("rect.y1: |value| must be at
//                     most 2^32 * min_distance = ...").
Status CheckRectBounds(const World& world, const Rect& rect, std::string_view field);

// The cost half of the rule, for a rectangle already known to be finite and
// ordered (a viewport grown by a margin, which may reach beyond the range):
// INVALID_ARGUMENT when its area exceeds limit.max_area d^2 or it crosses
// more than MaxRegionsCrossed regions; an overflowing area fails too. O(1).
Status CheckQueryCost(const World& world, const Rect& rect, const QueryLimit& limit,
                      std::string_view what);

}  // namespace scallop
