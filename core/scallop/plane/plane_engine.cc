// PlaneEngine: query validation, dependency closure, rank-by-rank parallel
// generation through the shared cache, and assembly of results.
#include "scallop/plane/plane_engine.h"

#include <algorithm>
#include <boost/asio/post.hpp>
#include <boost/asio/thread_pool.hpp>
#include <latch>
#include <map>
#include <set>

#include "scallop/plane/point_id.h"
#include "scallop/plane/query_rect.h"
#include "scallop/plane/region_exclusions.h"
#include "scallop/plane/world_layers.h"

namespace scallop {

PlaneEngine::PlaneEngine(const PlaneEngineOptions& options)
    : options_(options), cache_(options.cache_bytes) {
  if (options_.threads > 1) {
    pool_ = std::make_unique<boost::asio::thread_pool>(static_cast<size_t>(options_.threads));
  }
}

PlaneEngine::~PlaneEngine() {
  if (pool_) pool_->join();
}

Status PlaneEngine::ValidateQuery(const World& world, const Rect& rect) const {
  return CheckQueryRect(world, rect, {.max_area = options_.max_query_area});
}

std::vector<RegionKey> PlaneEngine::RegionsOverlapping(const World& world, const Rect& rect) {
  const RegionRange range = scallop::RegionsOverlapping(RegionLayout(world), rect);
  std::vector<RegionKey> keys;
  for (int64_t j = range.low.j; j <= range.high.j; ++j) {
    for (int64_t i = range.low.i; i <= range.high.i; ++i) keys.push_back({i, j});
  }
  return keys;
}

std::vector<RegionHandle> PlaneEngine::Resolve(const World& world,
                                               const std::vector<RegionKey>& wanted) {
  // Look up the wanted regions; only those that must be generated pull in
  // their lower-ranked neighbours, so a warm query costs one lookup a region.
  std::map<RegionKey, RegionHandle> resolved;
  std::set<RegionKey> to_generate[4];
  std::vector<std::pair<RegionKey, std::shared_future<RegionHandle>>> pending[4];
  std::set<RegionKey> seen;
  std::vector<RegionKey> stack(wanted.rbegin(), wanted.rend());
  while (!stack.empty()) {
    const RegionKey key = stack.back();
    stack.pop_back();
    if (!seen.insert(key).second) continue;
    RegionCache::Lookup lookup = cache_.Acquire(world, key);
    if (lookup.ready) {
      resolved.emplace(key, std::move(lookup.ready));
    } else if (!lookup.must_generate) {
      pending[RegionRank(key)].emplace_back(key, std::move(lookup.pending));
    } else {
      to_generate[RegionRank(key)].insert(key);
      for (const RegionKey& n : LowerRankedNeighbours(key)) stack.push_back(n);
    }
  }

  // A later layer's regions keep clear of the earlier layers' points: those
  // layers' regions are resolved first, here on the calling thread, so the
  // pool never waits on itself and dependencies run down (layer, rank).
  std::map<RegionKey, std::vector<ExclusionDisk>> exclusions;
  if (world.earlier_layers() != nullptr) {
    std::vector<RegionKey> keys;
    for (const std::set<RegionKey>& rank : to_generate)
      keys.insert(keys.end(), rank.begin(), rank.end());
    exclusions = RegionExclusions(
        world, keys, [this](const World& layer, const std::vector<RegionKey>& layer_keys) {
          return Resolve(layer, layer_keys);
        });
  }

  // Rank by rank: a region depends only on lower ranks, so once those are in
  // `resolved` (ours generated, others' awaited) the rank's regions are
  // independent and generate in parallel. Others' work of the same rank is
  // awaited only after ours is done, so no thread waits on a thread that
  // waits on it.
  for (int rank = 0; rank < 4; ++rank) {
    const std::vector<RegionKey> mine(to_generate[rank].begin(), to_generate[rank].end());
    std::vector<RegionHandle> generated(mine.size());
    auto generate = [&](size_t n) {
      std::vector<const RegionPoints*> neighbours;
      for (const RegionKey& dependency : LowerRankedNeighbours(mine[n])) {
        neighbours.push_back(resolved.at(dependency).get());
      }
      const auto disks = exclusions.find(mine[n]);
      auto region = std::make_shared<const RegionPoints>(GenerateRegion(
          world, mine[n], neighbours,
          disks == exclusions.end() ? std::span<const ExclusionDisk>{} : disks->second));
      cache_.Publish(world, mine[n], region);
      generated[n] = std::move(region);
    };
    if (pool_ && mine.size() > 1) {
      std::latch done(static_cast<std::ptrdiff_t>(mine.size()));
      for (size_t n = 0; n < mine.size(); ++n) {
        boost::asio::post(*pool_, [&, n] {
          generate(n);
          done.count_down();
        });
      }
      done.wait();
    } else {
      for (size_t n = 0; n < mine.size(); ++n) generate(n);
    }
    for (size_t n = 0; n < mine.size(); ++n) resolved.emplace(mine[n], std::move(generated[n]));
    for (auto& [key, future] : pending[rank]) resolved.emplace(key, future.get());
  }

  std::vector<RegionHandle> result;
  result.reserve(wanted.size());
  for (const RegionKey& key : wanted) result.push_back(resolved.at(key));
  return result;
}

namespace {

Status NoRegionsOfItsOwn() {
  return InvalidArgument(
      "world: a layered world has no regions of its own; ask its layers' worlds");
}

}  // namespace

StatusOr<std::vector<RegionHandle>> PlaneEngine::Regions(const World& world, const Rect& rect) {
  if (world.layers() != nullptr) return NoRegionsOfItsOwn();
  if (Status status = ValidateQuery(world, rect); !status.ok()) return status;
  return Resolve(world, RegionsOverlapping(world, rect));
}

std::optional<std::vector<RegionHandle>> PlaneEngine::CachedRegions(const World& world,
                                                                    const Rect& rect) {
  if (world.layers() != nullptr) return std::nullopt;
  std::vector<RegionHandle> regions;
  if (!cache_.PeekAll(world, RegionsOverlapping(world, rect), regions)) return std::nullopt;
  return regions;
}

StatusOr<PlanePoints> PlaneEngine::Points(const World& world, const Rect& rect, LayerMask layers) {
  if (Status status = ValidateQuery(world, rect); !status.ok()) return status;
  // Each part's regions first (a layered world's layers asked for, in order, or the world's
  // own), so that the answer is sized once and every point is copied once: growing it layer by
  // layer copied the earlier layers' points again and took fresh pages at each step.
  const WorldLayers* world_layers = world.layers();
  std::vector<std::pair<int, std::vector<RegionHandle>>> parts;
  size_t upper_bound = 0;
  for (int k = 0; k < (world_layers ? world_layers->count() : 1); ++k) {
    if (world_layers && ((layers >> k) & 1) == 0) continue;
    const World& own = world_layers ? world_layers->world(k) : world;
    if (Status status = world_layers ? ValidateQuery(own, rect) : Status(); !status.ok()) {
      return status;
    }
    std::vector<RegionHandle> regions = Resolve(own, RegionsOverlapping(own, rect));
    for (const RegionHandle& region : regions) upper_bound += region->points.size();
    parts.emplace_back(k, std::move(regions));
  }
  PlanePoints result;
  result.positions.reserve(upper_bound);
  result.ids.reserve(upper_bound);
  for (const auto& [k, regions] : parts) {
    const World& own = world_layers ? world_layers->world(k) : world;
    VisitPoints(regions, RegionLayout(own), rect, 0, upper_bound,
                [&](const Vec2& position, uint64_t id) {
                  result.positions.push_back(position);
                  result.ids.push_back(id);
                });
    if (world_layers) result.layers.resize(result.positions.size(), static_cast<uint8_t>(k));
  }
  return result;
}

StatusOr<int64_t> PlaneEngine::Count(const World& world, const Rect& rect) {
  if (Status status = ValidateQuery(world, rect); !status.ok()) return status;
  if (const WorldLayers* layers = world.layers()) {
    int64_t count = 0;
    for (int k = 0; k < layers->count(); ++k) {
      StatusOr<int64_t> layer = Count(layers->world(k), rect);
      if (!layer.ok()) return layer.status();
      count += *layer;
    }
    return count;
  }
  int64_t count = 0;
  for (const RegionHandle& region : Resolve(world, RegionsOverlapping(world, rect))) {
    count += std::count_if(region->points.begin(), region->points.end(),
                           [&](const Vec2& p) { return rect.Contains(p); });
  }
  return count;
}

StatusOr<RegionHandle> PlaneEngine::Region(const World& world, RegionKey key) {
  if (world.layers() != nullptr) return NoRegionsOfItsOwn();
  // Checked on the key, because the rectangle of an extreme key would overflow.
  const int64_t n = RegionLayout(world).regions_per_half_axis();
  if (key.i < -n || key.i >= n || key.j < -n || key.j >= n) {
    return OutOfRange("region: lies beyond the precision range of 2^32 * min_distance");
  }
  return Resolve(world, {key}).front();
}

}  // namespace scallop
