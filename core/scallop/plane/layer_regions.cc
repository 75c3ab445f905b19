// Per-layer region queries: each layer asked for is a query of its own world.
#include "scallop/plane/layer_regions.h"

#include "scallop/plane/world_layers.h"

namespace scallop {

std::vector<int> LayersAskedFor(const World& world, LayerMask mask) {
  const WorldLayers* layers = world.layers();
  if (layers == nullptr) return {-1};
  std::vector<int> asked;
  for (int k = 0; k < layers->count(); ++k) {
    if (((mask >> k) & 1) != 0) asked.push_back(k);
  }
  return asked;
}

const World& WorldOfLayer(const World& world, int layer) {
  return layer < 0 ? world : world.layers()->world(layer);
}

StatusOr<std::vector<LayerRegions>> QueryRegions(PlaneEngine& engine, const World& world,
                                                 const Rect& rect, LayerMask mask) {
  // The layered world's own rule first (its d is the smallest layer's), as Points applies it.
  if (Status status = engine.ValidateQuery(world, rect); !status.ok()) return status;
  std::vector<LayerRegions> parts;
  for (const int layer : LayersAskedFor(world, mask)) {
    const World& own = WorldOfLayer(world, layer);
    StatusOr<std::vector<RegionHandle>> regions = engine.Regions(own, rect);
    if (!regions.ok()) return regions.status();
    parts.push_back({layer, own, std::move(*regions)});
  }
  return parts;
}

std::optional<std::vector<LayerRegions>> CachedQueryRegions(PlaneEngine& engine, const World& world,
                                                            const Rect& rect, LayerMask mask) {
  std::vector<LayerRegions> parts;
  for (const int layer : LayersAskedFor(world, mask)) {
    const World& own = WorldOfLayer(world, layer);
    std::optional<std::vector<RegionHandle>> regions = engine.CachedRegions(own, rect);
    if (!regions) return std::nullopt;
    parts.push_back({layer, own, std::move(*regions)});
  }
  return parts;
}

}  // namespace scallop
