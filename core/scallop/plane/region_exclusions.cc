// RegionExclusions: one resolve of each earlier layer over the keys' bounding rectangle, then
// each key's disks from the regions around it, as its region is generated.
#include "scallop/plane/region_exclusions.h"

#include <algorithm>

#include "scallop/geometry/rect_distance.h"
#include "scallop/plane/region_generator.h"
#include "scallop/plane/world_layers.h"

namespace scallop {

RegionExclusions::RegionExclusions(const World& world, const std::vector<RegionKey>& keys,
                                   const ResolveRegions& resolve)
    : world_(&world) {
  if (keys.empty()) return;
  const EarlierLayers& earlier = *world.earlier_layers();
  // The sampled rectangles' bounds.
  Rect bounds = SampledRect(world, keys.front());
  for (const RegionKey& key : keys) {
    const Rect r = SampledRect(world, key);
    bounds = {std::min(bounds.x0, r.x0), std::min(bounds.y0, r.y0), std::max(bounds.x1, r.x1),
              std::max(bounds.y1, r.y1)};
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
    wanted.reserve(static_cast<size_t>(range.Count()));
    for (int64_t rj = range.low.j; rj <= range.high.j; ++rj) {
      for (int64_t ri = range.low.i; ri <= range.high.i; ++ri) wanted.push_back({ri, rj});
    }
    layers_.push_back({distance, layout, range, resolve(layer, wanted)});
  }
}

std::span<const ExclusionDisk> RegionExclusions::DisksFor(
    RegionKey key, std::vector<ExclusionDisk>& storage) const {
  size_t count = 0;
  const Rect sampled = SampledRect(*world_, key);
  for (const Layer& layer : layers_) {
    const double distance = layer.distance, squared = distance * distance;
    // The regions whose rectangle comes within D of the sampled one: every point farther is
    // farther from it than D. Inside `range`, which grew the keys' bounds by D.
    const RegionRange near = RegionsOverlapping(layer.layout, Grown(sampled, distance));
    const auto columns = static_cast<size_t>(layer.range.high.i - layer.range.low.i + 1);
    for (int64_t rj = near.low.j; rj <= near.high.j; ++rj) {
      for (int64_t ri = near.low.i; ri <= near.high.i; ++ri) {
        const std::vector<Vec2>& points =
            layer
                .regions[static_cast<size_t>(rj - layer.range.low.j) * columns +
                         static_cast<size_t>(ri - layer.range.low.i)]
                ->points;
        // Room for all (the storage only grows, so it is seldom filled twice), then each point
        // written and kept or not without a branch (whether a point is near cannot be
        // predicted).
        if (storage.size() < count + points.size()) storage.resize(2 * (count + points.size()));
        ExclusionDisk* disks = storage.data();
        for (const Vec2& p : points) {
          disks[count] = {p, distance};
          count += SquaredDistanceInLanes(sampled, p) < squared;
        }
      }
    }
  }
  return {storage.data(), count};
}

}  // namespace scallop
