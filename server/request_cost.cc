#include "server/request_cost.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "scallop/noise/nearest_lookup.h"
#include "scallop/plane/layer_regions.h"
#include "scallop/plane/query_rect.h"
#include "scallop/plane/world_layers.h"
#include "server/layer_choice.h"
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

// Nearest and NoiseGrid answer for one layer of a layered world: that layer's world.
template <typename Request>
bool ResolveLayerWorld(const WorldRegistry& worlds, const Request& request, World& world) {
  if (!ResolveWorld(worlds, request, world)) return false;
  int layer = -1;
  if (!LayerChoiceOf(world, request.layer(), "layer", layer).ok()) return false;
  if (layer >= 0) {
    // Copied out first: the layer's world is owned by `world`, which the assignment replaces
    // (assigning it in place read it after its owner freed it; ASan caught it).
    World own = WorldOfLayer(world, layer);
    world = std::move(own);
  }
  return true;
}

// Nearest and NoiseGrid on the box of their positions: each position reads its region's
// search grid (the 3 x 3 regions about it, shared by every position of the region), so the
// positions' regions bound the cost, as do their number and max_regions (a call in more is
// refused). On a radius-field world with masks a position near a mask may also need the
// brute force's square of half side NearestLookup::FallbackReach (32 r_max: about 12 x 12
// regions of 6 r_max): the regions of the box grown by that, or that square's per position,
// whichever is fewer.
int64_t NearestCost(const World& world, const Rect& box, int64_t positions, int64_t max_regions) {
  const int64_t plain = std::min({RegionsCost(world, box), positions, max_regions});
  const RadiusField* field = world.radius_field();
  // A later layer's positions near an earlier layer's exclusion disks may need the brute force
  // too: the disks leave the layer's own points farther than its spacing.
  const bool may_fall_back =
      (field != nullptr && field->HasMask()) || world.earlier_layers() != nullptr;
  if (!may_fall_back) return plain;
  const double reach = NearestLookup::FallbackReach(world);
  const double limit = RegionLayout(world).precision_limit();
  // Cut to the range, where the world has its points (and RegionsCost counts).
  const Rect grown{std::max(box.x0 - reach, -limit), std::max(box.y0 - reach, -limit),
                   std::min(box.x1 + reach, limit), std::min(box.y1 + reach, limit)};
  const int64_t per_position = RegionsCost(world, {-reach, -reach, reach, reach});
  return std::min({RegionsCost(world, grown), plain * per_position});
}

}  // namespace

int64_t RegionsCost(const World& world, const Rect& rect) {
  if (const WorldLayers* layers = world.layers()) {
    // Every layer's own regions, whatever the filter: a later layer's regions read the earlier
    // layers' (whose halo, farther out, this does not count: it is a few regions a layer).
    int64_t cost = 0;
    for (int k = 0; k < layers->count(); ++k) cost += RegionsCost(layers->world(k), rect);
    return cost;
  }
  if (!CheckRectBounds(world, rect, "rect").ok()) return 1;
  const double count = RegionsOverlapping(RegionLayout(world), rect).Count();
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
  const WorldLayers* layers = world.layers();
  // VerifyWorldRect's halo.
  const double halo = layers != nullptr
                          ? std::max(2 * layers->largest_spacing(), layers->largest_exclusion())
                          : 2 * world.max_spacing();
  return RegionsCost(world, {rect.x0 - halo, rect.y0 - halo, rect.x1 + halo, rect.y1 + halo});
}

int64_t RequestCost(const WorldRegistry& worlds, const v1::NoiseGridRequest& request,
                    int64_t max_regions) {
  World world;
  if (!ResolveLayerWorld(worlds, request, world) || request.width() < 1 || request.height() < 1) {
    return 1;
  }
  const double x0 = request.origin_x(), y0 = request.origin_y(), step = request.step();
  // Samples sit at origin + k step, k < width: the last one is inside the box.
  return NearestCost(world,
                     {x0, y0, std::nextafter(x0 + step * (request.width() - 1), INFINITY),
                      std::nextafter(y0 + step * (request.height() - 1), INFINITY)},
                     int64_t{request.width()} * request.height(), max_regions);
}

int64_t RequestCost(const WorldRegistry& worlds, const v1::NearestRequest& request,
                    int64_t max_regions) {
  World world;
  const auto& xs = request.positions().xs();
  const auto& ys = request.positions().ys();
  if (!ResolveLayerWorld(worlds, request, world) || xs.empty() || xs.size() != ys.size()) {
    return 1;
  }
  const auto [x0, x1] = std::minmax_element(xs.begin(), xs.end());
  const auto [y0, y1] = std::minmax_element(ys.begin(), ys.end());
  return NearestCost(world,
                     {*x0, *y0, std::nextafter(*x1, INFINITY), std::nextafter(*y1, INFINITY)},
                     static_cast<int64_t>(xs.size()), max_regions);
}

}  // namespace scallop::server
