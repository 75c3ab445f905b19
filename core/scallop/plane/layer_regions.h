// The regions a query of any world reads, layer by layer: one part for a world without layers,
// one part per layer asked for of a layered world (each layer's regions are its own world's).
// What a server copies points from straight into its messages, with their layer, as
// PlaneEngine::Regions and VisitPoints do for one world. docs/design.md, "Layered worlds".
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "scallop/base/status.h"
#include "scallop/plane/plane_engine.h"
#include "scallop/plane/region_layout.h"

namespace scallop {

// One world's regions of a query: a layer's (layer >= 0, world its layer world) or, for a world
// without layers, the world's own (layer -1).
struct LayerRegions {
  int layer = -1;
  World world;
  std::vector<RegionHandle> regions;
};

// The layers of `world` that `mask` asks for, in the layers' order; {-1} for a world without
// layers (which ignores the mask).
std::vector<int> LayersAskedFor(const World& world, LayerMask mask);

// The world whose regions hold `layer`'s points (LayersAskedFor's numbers; -1: `world` itself).
const World& WorldOfLayer(const World& world, int layer);

// The regions of every layer asked for, in the layers' order, each in query order: what
// PlaneEngine::Points of (world, rect, mask) copies from. Cold layers are generated with the
// earlier layers they keep clear of. Errors as PlaneEngine::Regions of each layer's world.
StatusOr<std::vector<LayerRegions>> QueryRegions(PlaneEngine& engine, const World& world,
                                                 const Rect& rect, LayerMask mask = kAllLayers);

// The same when every region of every layer asked for is cached now, else nullopt, having
// generated and waited on nothing (PlaneEngine::CachedRegions).
std::optional<std::vector<LayerRegions>> CachedQueryRegions(PlaneEngine& engine, const World& world,
                                                            const Rect& rect,
                                                            LayerMask mask = kAllLayers);

// Calls start(part) before each part, then visit(position, id) for its points inside `rect`, in
// the order PlaneEngine::Points gives them (layer by layer), skipping the first `begin` and
// stopping before index `end` of that sequence; returns how many points lie in `rect` in all.
template <typename Start, typename Visit>
size_t VisitLayerPoints(const std::vector<LayerRegions>& parts, const Rect& rect, size_t begin,
                        size_t end, Start start, Visit visit) {
  size_t before = 0;  // points inside in the parts before this one
  for (const LayerRegions& part : parts) {
    start(part);
    before +=
        VisitPoints(part.regions, RegionLayout(part.world), rect,
                    begin > before ? begin - before : 0, end > before ? end - before : 0, visit);
  }
  return before;
}

}  // namespace scallop
