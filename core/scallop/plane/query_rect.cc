// The rectangle rule: finite, ordered, within the precision range, within the
// area and region limits; and the regions a rectangle overlaps.
#include "scallop/plane/query_rect.h"

#include <cmath>
#include <string>
#include <utility>

#include "scallop/base/number_text.h"

namespace scallop {

RegionRange RegionsOverlapping(const RegionLayout& layout, const Rect& rect) {
  return {layout.RegionOf(rect.x0, rect.y0),
          layout.RegionOf(std::nextafter(rect.x1, rect.x0), std::nextafter(rect.y1, rect.y0))};
}

double MaxRegionsCrossed(double max_area) { return max_area / 64 + 16; }

std::string RegionSideText(const World& world) {
  if (world.radius_field() == nullptr) return NumberText(kRegionSideInD) + " min_distance";
  return NumberText(kFieldRegionSideInRMax) + " r_max (r_max = " + NumberText(world.max_spacing()) +
         ")";
}

Status CheckQueryRect(const World& world, const Rect& rect, const QueryLimit& limit,
                      std::string_view field) {
  if (Status status = CheckRectBounds(world, rect, field); !status.ok()) return status;
  return CheckQueryCost(world, rect, limit, field);
}

Status CheckRectBounds(const World& world, const Rect& rect, std::string_view field) {
  const std::string name(field);
  const std::pair<const char*, double> corners[] = {
      {".x0", rect.x0}, {".y0", rect.y0}, {".x1", rect.x1}, {".y1", rect.y1}};
  const double range = RegionLayout(world).precision_limit();
  for (const auto& [corner, value] : corners) {
    if (!std::isfinite(value)) return InvalidArgument(name + corner + ": must be finite");
    if (std::abs(value) > range) {
      return OutOfRange(name + corner + ": |value| must be at most 2^32 * min_distance = " +
                        NumberText(range) + ", got " + NumberText(value));
    }
  }
  if (!(rect.x0 < rect.x1)) return InvalidArgument(name + ": x0 must be less than x1");
  if (!(rect.y0 < rect.y1)) return InvalidArgument(name + ": y0 must be less than y1");
  return Status::Ok();
}

Status CheckQueryCost(const World& world, const Rect& rect, const QueryLimit& limit,
                      std::string_view what) {
  const double d = world.min_distance();
  const std::string limit_name(limit.name);
  // Width and height over d first: their product in world units could overflow.
  const double area = rect.Width() / d * (rect.Height() / d);
  if (!(area <= limit.max_area)) {
    return InvalidArgument(std::string(what) + ": area is " + NumberText(area) +
                           " min_distance^2, must be at most " + NumberText(limit.max_area) + " (" +
                           limit_name + ")");
  }
  const double max_regions = MaxRegionsCrossed(limit.max_area);
  const double regions = RegionsOverlapping(RegionLayout(world), rect).Count();
  if (regions > max_regions) {
    return InvalidArgument(std::string(what) + ": crosses " + NumberText(regions) + " regions of " +
                           RegionSideText(world) + ", at most " + NumberText(max_regions) + " (" +
                           limit_name + " / 64 + 16)");
  }
  return Status::Ok();
}

}  // namespace scallop
