// RegionExclusions: one resolve of each earlier layer over the keys' bounding rectangle, then
// each key's disks from the regions around it.
#include "scallop/plane/region_exclusions.h"

#include <algorithm>

#include "scallop/plane/query_rect.h"
#include "scallop/plane/region_generator.h"
#include "scallop/plane/world_layers.h"

namespace scallop {

std::map<RegionKey, std::vector<ExclusionDisk>> RegionExclusions(const World& world,
                                                                 const std::vector<RegionKey>& keys,
                                                                 const ResolveRegions& resolve) {
  std::map<RegionKey, std::vector<ExclusionDisk>> result;
  if (keys.empty()) return result;
  const EarlierLayers& earlier = *world.earlier_layers();
  Rect bounds = SampledRect(world, keys.front());
  for (const RegionKey& key : keys) {
    const Rect r = SampledRect(world, key);
    bounds = {std::min(bounds.x0, r.x0), std::min(bounds.y0, r.y0), std::max(bounds.x1, r.x1),
              std::max(bounds.y1, r.y1)};
    result[key];
  }
  for (size_t j = 0; j < earlier.worlds.size(); ++j) {
    const double distance = earlier.distances[j];
    if (!(distance > 0.0)) continue;
    const World& layer = earlier.worlds[j];
    const RegionLayout layout(layer);
    // The earlier layer's regions over every key's reach, resolved at once (on this thread,
    // before the keys are generated: the engine's pool never waits on itself).
    const RegionRange range = RegionsOverlapping(layout, Grown(bounds, distance));
    std::vector<RegionKey> wanted;
    for (int64_t rj = range.low.j; rj <= range.high.j; ++rj) {
      for (int64_t ri = range.low.i; ri <= range.high.i; ++ri) wanted.push_back({ri, rj});
    }
    const std::vector<RegionHandle> regions = resolve(layer, wanted);
    const auto columns = static_cast<size_t>(range.high.i - range.low.i + 1);
    const double squared = distance * distance;
    for (auto& [key, disks] : result) {
      const Rect sampled = SampledRect(world, key);
      const RegionRange near = RegionsOverlapping(layout, Grown(sampled, distance));
      for (int64_t rj = near.low.j; rj <= near.high.j; ++rj) {
        for (int64_t ri = near.low.i; ri <= near.high.i; ++ri) {
          const size_t at = static_cast<size_t>(rj - range.low.j) * columns +
                            static_cast<size_t>(ri - range.low.i);
          // A region's points are exactly the layer's points in its rectangle: each once.
          for (const Vec2& p : regions[at]->points) {
            if (SquaredDistance(sampled, p) < squared) disks.push_back({p, distance});
          }
        }
      }
    }
  }
  return result;
}

}  // namespace scallop
