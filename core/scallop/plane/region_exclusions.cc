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
  // The sampled rectangles' bounds, and the block of region indices that holds the keys (for
  // a dense table of the keys by place, below).
  Rect bounds = SampledRect(world, keys.front());
  RegionRange key_range{keys.front(), keys.front()};
  for (const RegionKey& key : keys) {
    const Rect r = SampledRect(world, key);
    bounds = {std::min(bounds.x0, r.x0), std::min(bounds.y0, r.y0), std::max(bounds.x1, r.x1),
              std::max(bounds.y1, r.y1)};
    key_range.low = {std::min(key_range.low.i, key.i), std::min(key_range.low.j, key.j)};
    key_range.high = {std::max(key_range.high.i, key.i), std::max(key_range.high.j, key.j)};
    result[key];
  }
  const RegionLayout own_layout(world);
  const auto key_columns = static_cast<size_t>(key_range.high.i - key_range.low.i + 1);
  struct Target {
    std::vector<ExclusionDisk>* disks;
    Rect sampled;
    RegionRange near;  // the earlier layer's regions near `sampled`
  };
  std::vector<Target> storage;
  storage.reserve(result.size());
  std::vector<Target*> targets(key_columns *
                               static_cast<size_t>(key_range.high.j - key_range.low.j + 1));
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
    storage.clear();
    for (auto& [key, disks] : result) {
      const Rect sampled = SampledRect(world, key);
      storage.push_back({&disks, sampled, RegionsOverlapping(layout, Grown(sampled, distance))});
      targets[static_cast<size_t>(key.j - key_range.low.j) * key_columns +
              static_cast<size_t>(key.i - key_range.low.i)] = &storage.back();
    }
    // Beyond this from a point no key's sampled rectangle comes within D of it (a hundredth
    // more for rounding: a key found in excess is judged by the exact tests anyway).
    const double reach_of_key = 1.01 * (SamplingMargin(world) + distance);
    const double squared = distance * distance;
    // Each point is offered to the few keys whose sampled rectangle it may be near (found by
    // the later layer's layout), not to every key near its region: a trees' region is near
    // about 50 rocks' regions. A key takes a point under the very tests it always did (the
    // point's region near the key's rectangle, the point within D of it), and its points come
    // in the same order (regions in rows, then points in index order), so its list is the same.
    const Rect reach_of_point{-reach_of_key, -reach_of_key, reach_of_key, reach_of_key};
    for (int64_t rj = range.low.j; rj <= range.high.j; ++rj) {
      for (int64_t ri = range.low.i; ri <= range.high.i; ++ri) {
        const size_t at =
            static_cast<size_t>(rj - range.low.j) * columns + static_cast<size_t>(ri - range.low.i);
        for (const Vec2& p : regions[at]->points) {
          const RegionRange keys_near =
              RegionsOverlapping(own_layout, {p.x + reach_of_point.x0, p.y + reach_of_point.y0,
                                              p.x + reach_of_point.x1, p.y + reach_of_point.y1});
          for (int64_t kj = std::max(keys_near.low.j, key_range.low.j);
               kj <= std::min(keys_near.high.j, key_range.high.j); ++kj) {
            for (int64_t ki = std::max(keys_near.low.i, key_range.low.i);
                 ki <= std::min(keys_near.high.i, key_range.high.i); ++ki) {
              Target* target = targets[static_cast<size_t>(kj - key_range.low.j) * key_columns +
                                       static_cast<size_t>(ki - key_range.low.i)];
              if (target == nullptr) continue;
              const RegionRange& near = target->near;
              if (ri < near.low.i || ri > near.high.i || rj < near.low.j || rj > near.high.j) {
                continue;
              }
              if (SquaredDistance(target->sampled, p) < squared) {
                target->disks->push_back({p, distance});
              }
            }
          }
        }
      }
    }
  }
  return result;
}

}  // namespace scallop
