// Rectangle checks: presence, the engine's validation, area and regions crossed.
#include "query_limits.h"

#include <cmath>
#include <sstream>
#include <string>

#include "scallop/plane/region_layout.h"
#include "status_mapping.h"

namespace scallop::server {
namespace {

// "4e+06", "15641": shortest readable text, unlike std::to_string's fixed six decimals.
std::string Number(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

}  // namespace

double RegionsCrossed(const World& world, const Rect& rect) {
  const RegionLayout layout(world.min_distance);
  // The half-open rectangle ends just below x1 and y1.
  const RegionKey low = layout.RegionOf(rect.x0, rect.y0);
  const RegionKey high =
      layout.RegionOf(std::nextafter(rect.x1, rect.x0), std::nextafter(rect.y1, rect.y0));
  return (static_cast<double>(high.i - low.i) + 1) * (static_cast<double>(high.j - low.j) + 1);
}

grpc::Status CheckQueryRect(const PlaneEngine& engine, const World& world, bool has_rect,
                            const Rect& rect, double max_area, const char* limit_name) {
  if (!has_rect) {
    return {grpc::StatusCode::INVALID_ARGUMENT,
            "rect: required, the half-open rectangle [x0, x1) x [y0, y1)"};
  }
  if (Status status = engine.ValidateQuery(world, rect); !status.ok()) return ToGrpcStatus(status);
  const double d = world.min_distance;
  const double area = rect.Width() / d * (rect.Height() / d);
  if (area > max_area) {
    return {grpc::StatusCode::INVALID_ARGUMENT, "rect: area is " + Number(area) +
                                                    " min_distance^2, must be at most " +
                                                    Number(max_area) + " (" + limit_name + ")"};
  }
  const double max_regions = max_area / 64 + 16;
  if (const double regions = RegionsCrossed(world, rect); regions > max_regions) {
    return {grpc::StatusCode::INVALID_ARGUMENT,
            "rect: crosses " + Number(regions) + " regions of 16 min_distance, at most " +
                Number(max_regions) + " (" + limit_name + " / 64 + 16)"};
  }
  return grpc::Status::OK;
}

}  // namespace scallop::server
