#include "server/request_cost.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "scallop/plane/query_rect.h"
#include "world_messages.h"

namespace scallop::server {
namespace {

template <typename Request>
bool ResolveWorld(const WorldRegistry& worlds, const Request& request, World& world) {
  ResolvedWorld resolved;
  if (!worlds.Resolve(request, resolved).ok()) return false;
  world = resolved.world;
  return true;
}

}  // namespace

int64_t RegionsCost(const World& world, const Rect& rect) {
  if (!CheckRectBounds(world, rect, "rect").ok()) return 1;
  const double count = RegionsOverlapping(RegionLayout(world.min_distance()), rect).Count();
  // Far beyond any budget already; the cast stays defined.
  return static_cast<int64_t>(std::min(count, 1e15));
}

int64_t RequestCost(const WorldRegistry& worlds, const v1::GetPointsRequest& request) {
  World world;
  if (!ResolveWorld(worlds, request, world)) return 1;
  return RegionsCost(world, RectFromMessage(request.rect()));
}

int64_t RequestCost(const WorldRegistry& worlds, const v1::VerifyRequest& request) {
  World world;
  if (!ResolveWorld(worlds, request, world)) return 1;
  const Rect rect = RectFromMessage(request.rect());
  const double halo = 2 * world.min_distance();
  return RegionsCost(world, {rect.x0 - halo, rect.y0 - halo, rect.x1 + halo, rect.y1 + halo});
}

int64_t RequestCost(const WorldRegistry& worlds, const v1::NoiseGridRequest& request,
                    int64_t max_regions) {
  World world;
  if (!ResolveWorld(worlds, request, world) || request.width() < 1 || request.height() < 1) {
    return 1;
  }
  const double x0 = request.origin_x(), y0 = request.origin_y(), step = request.step();
  // Samples sit at origin + k step, k < width: the last one is inside the box.
  const int64_t box =
      RegionsCost(world, {x0, y0, std::nextafter(x0 + step * (request.width() - 1), INFINITY),
                          std::nextafter(y0 + step * (request.height() - 1), INFINITY)});
  return std::min({box, int64_t{request.width()} * request.height(), max_regions});
}

int64_t RequestCost(const WorldRegistry& worlds, const v1::NearestRequest& request,
                    int64_t max_regions) {
  World world;
  const auto& xs = request.positions().xs();
  const auto& ys = request.positions().ys();
  if (!ResolveWorld(worlds, request, world) || xs.empty() || xs.size() != ys.size()) return 1;
  const auto [x0, x1] = std::minmax_element(xs.begin(), xs.end());
  const auto [y0, y1] = std::minmax_element(ys.begin(), ys.end());
  const int64_t box =
      RegionsCost(world, {*x0, *y0, std::nextafter(*x1, INFINITY), std::nextafter(*y1, INFINITY)});
  return std::min({box, static_cast<int64_t>(xs.size()), max_regions});
}

}  // namespace scallop::server
