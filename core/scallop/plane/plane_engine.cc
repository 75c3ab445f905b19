// PlaneEngine: query validation, dependency closure, generation in dependency
// order on the engine's threads through the shared cache, and assembly of results.
#include "scallop/plane/plane_engine.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <boost/asio/post.hpp>
#include <boost/asio/thread_pool.hpp>
#include <functional>
#include <future>
#include <latch>
#include <map>
#include <optional>

#include "scallop/plane/point_id.h"
#include "scallop/plane/query_rect.h"
#include "scallop/plane/region_exclusions.h"
#include "scallop/plane/region_scratch.h"
#include "scallop/plane/world_layers.h"

namespace scallop {

PlaneEngine::PlaneEngine(const PlaneEngineOptions& options)
    : options_(options),
      cache_(options.cache_bytes),
      // One a generating thread: the pool's, and callers generating on their own.
      scratch_(static_cast<size_t>(options.threads) + 8) {
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
  // Sized once: grown key by key, a warm 64 d tile's 25 keys took six allocations.
  // Every caller has checked the query (ValidateQuery), which bounds the count.
  keys.reserve(static_cast<size_t>(range.Count()));
  for (int64_t j = range.low.j; j <= range.high.j; ++j) {
    for (int64_t i = range.low.i; i <= range.high.i; ++i) keys.push_back({i, j});
  }
  return keys;
}

namespace {

// A region of a query's plan that is not ready: ours to generate, or another
// caller's (`pending`) to await. Written before the schedule starts but for
// `region` (set once it is generated or awaited, before its dependents hear
// of it) and `waiting_for` (counted down as its dependencies are set).
struct PlannedRegion {
  RegionKey key;
  std::shared_future<RegionHandle> pending;  // valid: another caller generates it
  std::vector<size_t> dependents;            // our planned regions that need this one
  std::atomic<int> waiting_for{0};           // ours: lower-ranked neighbours not yet set
  RegionHandle region;
};

}  // namespace

std::vector<RegionHandle> PlaneEngine::Resolve(const World& world,
                                               const std::vector<RegionKey>& wanted) {
  // Look up the wanted regions; only those that must be generated pull in
  // their lower-ranked neighbours, so a warm query costs one lookup a region.
  std::map<RegionKey, RegionHandle> ready;
  std::map<RegionKey, size_t> planned;  // key -> its index in `plan`
  std::vector<std::pair<RegionKey, std::shared_future<RegionHandle>>> lookups;
  std::vector<RegionKey> stack(wanted.rbegin(), wanted.rend());
  while (!stack.empty()) {
    const RegionKey key = stack.back();
    stack.pop_back();
    if (ready.contains(key) || planned.contains(key)) continue;
    RegionCache::Lookup lookup = cache_.Acquire(world, key);
    if (lookup.ready) {
      ready.emplace(key, std::move(lookup.ready));
      continue;
    }
    planned.emplace(key, lookups.size());
    if (lookup.must_generate) {
      for (const RegionKey& n : LowerRankedNeighbours(key)) stack.push_back(n);
    }
    lookups.emplace_back(key, std::move(lookup.pending));
  }

  // A later layer's regions keep clear of the earlier layers' points: those
  // layers' regions are resolved first, here on the calling thread, so the
  // pool never waits on itself and dependencies run down (layer, rank).
  // Each region's disks are listed from them as it is generated.
  std::optional<RegionExclusions> exclusions;
  if (world.earlier_layers() != nullptr && !lookups.empty()) {
    std::vector<RegionKey> keys;
    for (const auto& [key, pending] : lookups) {
      if (!pending.valid()) keys.push_back(key);
    }
    exclusions.emplace(world, keys,
                       [this](const World& layer, const std::vector<RegionKey>& layer_keys) {
                         return Resolve(layer, layer_keys);
                       });
  }

  // The dependency graph: a region of ours waits for its lower-ranked
  // neighbours that are not ready yet (ours or others').
  std::vector<PlannedRegion> plan(lookups.size());
  std::vector<size_t> others;  // indices in `plan` of others' regions, by rank
  size_t ours = 0;
  for (size_t n = 0; n < plan.size(); ++n) {
    plan[n].key = lookups[n].first;
    plan[n].pending = std::move(lookups[n].second);
    if (plan[n].pending.valid()) {
      others.push_back(n);
      continue;
    }
    ++ours;
    for (const RegionKey& dependency : LowerRankedNeighbours(plan[n].key)) {
      if (const auto it = planned.find(dependency); it != planned.end()) {
        plan[it->second].dependents.push_back(n);
        plan[n].waiting_for.fetch_add(1, std::memory_order_relaxed);
      }
    }
  }
  std::stable_sort(others.begin(), others.end(), [&](size_t a, size_t b) {
    return RegionRank(plan[a].key) < RegionRank(plan[b].key);
  });

  // A region of ours starts as soon as its last dependency is set: a region
  // is a pure function of its lower-ranked neighbours, so the order changes
  // no bit, and no thread idles at a rank's end while another still works.
  // Pool tasks never block. Without a pool (or for one region), the calling
  // thread runs the ready regions from a queue.
  const bool on_pool = pool_ && ours > 1;
  std::latch done(static_cast<std::ptrdiff_t>(ours));
  std::vector<size_t> queue;
  std::function<void(size_t)> generate;
  auto start = [&](size_t n) {
    if (on_pool) {
      boost::asio::post(*pool_, [&generate, n] { generate(n); });
    } else {
      queue.push_back(n);
    }
  };
  // Sets plan[n]'s region and starts the dependents that waited for it last.
  auto set = [&](size_t n, RegionHandle region) {
    plan[n].region = std::move(region);
    for (const size_t dependent : plan[n].dependents) {
      if (plan[dependent].waiting_for.fetch_sub(1, std::memory_order_acq_rel) == 1) {
        start(dependent);
      }
    }
  };
  generate = [&](size_t n) {
    const RegionKey key = plan[n].key;
    std::array<const RegionPoints*, 8> neighbours;  // in place: no allocation a region
    size_t neighbour_count = 0;
    for (const RegionKey& dependency : LowerRankedNeighbours(key)) {
      const auto it = ready.find(dependency);
      neighbours[neighbour_count++] =
          it != ready.end() ? it->second.get() : plan[planned.at(dependency)].region.get();
    }
    std::unique_ptr<RegionScratch> scratch = scratch_.Take();
    std::span<const ExclusionDisk> disks;
    if (exclusions) disks = exclusions->DisksFor(key, scratch->exclusions);
    if (options_.observer != nullptr) options_.observer->Started(world, key);
    auto region = std::make_shared<const RegionPoints>(GenerateRegion(
        world, key, std::span(neighbours.data(), neighbour_count), disks, scratch.get()));
    if (options_.observer != nullptr) options_.observer->Finished(world, key);
    scratch_.Return(std::move(scratch));
    cache_.Publish(world, key, region);
    set(n, std::move(region));
    done.count_down();  // last: the caller may return once every region counted down
  };
  auto run_queue = [&] {
    for (size_t next = 0; next < queue.size(); ++next) generate(queue[next]);
    queue.clear();
  };

  // Others' regions are awaited in rank order, after ours that are ready:
  // a caller waits on a region of rank r only once its own regions of ranks
  // up to r can run without it, so no thread waits on a thread that waits on
  // it.
  std::vector<size_t> first;  // all found before any starts, which would count others down
  for (size_t n = 0; n < plan.size(); ++n) {
    if (!plan[n].pending.valid() && plan[n].waiting_for.load(std::memory_order_relaxed) == 0) {
      first.push_back(n);
    }
  }
  for (const size_t n : first) start(n);
  run_queue();
  for (const size_t n : others) {
    set(n, plan[n].pending.get());
    run_queue();
  }
  done.wait();

  std::vector<RegionHandle> result;
  result.reserve(wanted.size());
  for (const RegionKey& key : wanted) {
    const auto it = ready.find(key);
    result.push_back(it != ready.end() ? it->second : plan[planned.at(key)].region);
  }
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
