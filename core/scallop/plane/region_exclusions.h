// What the regions of a later layer keep clear of: the earlier layers' points near each region
// (issue 19; docs/design.md, "Layers"). The plane engine resolves the earlier layers' regions
// over one rectangle that holds every region it must generate, then hands each region its own.
#pragma once

#include <functional>
#include <map>
#include <vector>

#include "scallop/plane/region_cache.h"
#include "scallop/plane/region_layout.h"
#include "scallop/plane/world.h"
#include "scallop/sampling/sampling_problem.h"

namespace scallop {

// Generated regions of `world`, all of `keys` in their order (the engine's Resolve).
using ResolveRegions = std::function<std::vector<RegionHandle>(const World& world,
                                                               const std::vector<RegionKey>& keys)>;

// For each of `keys`, regions of a later layer's world (REQUIRES: world.earlier_layers()), the
// exclusion disks GenerateRegion takes: for each earlier layer j in generation order, each of its
// points p with SquaredDistance(SampledRect(world, key), p) < D_j^2 (a farther point excludes no
// spot the run can reach), radius D_j; earlier layers with D_j = 0 give none. Within a layer,
// points come in region order (rows, then columns) and index order, so the list is a pure
// function of the world and the key. Cost: one `resolve` per earlier layer over the rectangle
// holding every key's sampled rectangle grown by that layer's D, then a scan of the regions
// near each key.
std::map<RegionKey, std::vector<ExclusionDisk>> RegionExclusions(const World& world,
                                                                 const std::vector<RegionKey>& keys,
                                                                 const ResolveRegions& resolve);

}  // namespace scallop
