// What the regions of a later layer keep clear of: the earlier layers' points near each region
// (issue 19; docs/design.md, "Layers"). The plane engine resolves the earlier layers' regions
// over one rectangle that holds every region it must generate, then each region's run takes its
// own disks from them.
#pragma once

#include <functional>
#include <span>
#include <vector>

#include "scallop/plane/query_rect.h"
#include "scallop/plane/region_cache.h"
#include "scallop/plane/region_layout.h"
#include "scallop/plane/world.h"
#include "scallop/sampling/sampling_problem.h"

namespace scallop {

// Generated regions of `world`, all of `keys` in their order (the engine's Resolve).
using ResolveRegions = std::function<std::vector<RegionHandle>(const World& world,
                                                               const std::vector<RegionKey>& keys)>;

// The earlier layers' regions around a set of keys of a later layer's world, held so that each
// key's exclusion disks can be listed when its region is generated: listed then, the list is
// read while it is still in cache, and no list waits in memory for its region (a forest's 250k
// query has 1,724 lists, 176 disks each on average, 7 MB that were all built before any was
// read, in a map).
// Thread-safe for concurrent DisksFor calls (it only reads what it holds).
class RegionExclusions {
 public:
  // For `keys`, regions of a later layer's world (REQUIRES: world.earlier_layers() not null):
  // one `resolve` per earlier layer with D > 0, over the rectangle that holds every key's
  // sampled rectangle grown by that layer's D. Nothing for no keys.
  RegionExclusions(const World& world, const std::vector<RegionKey>& keys,
                   const ResolveRegions& resolve);

  // The exclusion disks GenerateRegion takes for `key` (REQUIRES: one of the keys given), in
  // `storage` (grown when too small, never shrunk: its elements past the answer are left as
  // they are): for each earlier layer j in generation order, each of its points p with
  // SquaredDistance(SampledRect(world, key), p) < D_j^2 (a farther point excludes no spot the
  // run can reach), radius D_j; earlier layers with D_j = 0 give none. Within a layer, points
  // come in region order (rows, then columns) and index order, so the list is a pure function
  // of the world and the key. Cost: a test of each point of the few earlier regions within D_j
  // of the key's sampled rectangle (about 1,000 a region in a forest's 250k query).
  std::span<const ExclusionDisk> DisksFor(RegionKey key, std::vector<ExclusionDisk>& storage) const;

 private:
  // One earlier layer's regions over the keys' reach.
  struct Layer {
    double distance;
    RegionLayout layout;
    RegionRange range;
    std::vector<RegionHandle> regions;  // range's, by rows, then columns
  };

  const World* world_;
  std::vector<Layer> layers_;
};

}  // namespace scallop
