// PlaneEngine: the infinite-plane queries. Any rectangle of any world, its
// points exactly as the world defines them, whatever the query history, the
// tiling, the cache state or the thread count. Thread-safe: one engine serves
// every request of a server.
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <type_traits>
#include <utility>
#include <vector>

#include "scallop/base/scratch_pool.h"
#include "scallop/base/status.h"
#include "scallop/geometry/rect.h"
#include "scallop/plane/point_id.h"
#include "scallop/plane/region_cache.h"
#include "scallop/plane/region_layout.h"
#include "scallop/plane/world.h"

namespace boost::asio {
class thread_pool;
}

namespace scallop {

struct RegionScratch;

// Told on the generating thread when a region's generation starts and when it
// has finished (before the region is published to the cache and to the
// regions that wait for it): for tests and tracing. Several threads call it
// at once, so an implementation must be thread-safe.
class RegionGenerationObserver {
 public:
  virtual ~RegionGenerationObserver() = default;
  virtual void Started(const World& world, RegionKey key) = 0;
  virtual void Finished(const World& world, RegionKey key) = 0;
};

struct PlaneEngineOptions {
  // Cache budget in bytes (about 32 bytes per point for A3).
  int64_t cache_bytes = int64_t{512} << 20;
  // Threads that generate regions; 1 generates on the calling thread.
  int threads = 2;
  // Largest query area, in units of d^2 (1e8 d^2 is about 85M points); a
  // server sets it to the largest of its methods' limits.
  double max_query_area = 1e8;
  // Not owned; null, or outlives the engine. Two calls a generated region.
  RegionGenerationObserver* observer = nullptr;
};

// Points of a query, in a deterministic order: regions by row (j), then
// column (i), ascending; within a region, by point index (point_id.h).
// A layered world's points come layer by layer, in the layers' order (world_layers.h), each
// layer's in that order; a point is named by its layer and its id, which is its id in the
// layer's own world.
struct PlanePoints {
  std::vector<Vec2> positions;
  std::vector<uint64_t> ids;  // ids[k] is the id of positions[k] (point_id.h)
  // A layered world's: layers[k] is the layer of positions[k]. Empty for other worlds.
  std::vector<uint8_t> layers;
};

// A set of a layered world's layers, bit k for layer k.
using LayerMask = uint32_t;
inline constexpr LayerMask kAllLayers = ~LayerMask{0};

class PlaneEngine {
 public:
  explicit PlaneEngine(const PlaneEngineOptions& options);
  ~PlaneEngine();
  PlaneEngine(const PlaneEngine&) = delete;
  PlaneEngine& operator=(const PlaneEngine&) = delete;

  // The world's points in the half-open rectangle. Cost: O(area / d^2) for
  // the regions it overlaps plus a halo of at most 2 regions on each side
  // when cold; a copy when warm.
  // Rejects what CheckQueryRect (query_rect.h) rejects under max_query_area:
  // INVALID_ARGUMENT for a non-finite, empty or inverted rectangle, one larger
  // than max_query_area d^2 or crossing more than max_query_area / 64 + 16
  // regions; OUT_OF_RANGE for a corner beyond 2^32 d.
  // A layered world: the layers in `layers` (bits beyond its count are
  // ignored), each layer a query of its own world, which generates the
  // earlier layers' regions its regions keep clear of (RegionExclusions).
  StatusOr<PlanePoints> Points(const World& world, const Rect& rect, LayerMask layers = kAllLayers);

  // The regions a query of the rectangle reads, in query order (rows, then
  // columns), shared: what Points copies from, for callers that copy the
  // points straight into their own form with VisitPoints. Same cost and errors.
  // A layered world has no regions of its own (INVALID_ARGUMENT naming
  // "world"): ask its layers' worlds.
  StatusOr<std::vector<RegionHandle>> Regions(const World& world, const Rect& rect);

  // The same regions if every one is cached now, else nullopt, having
  // generated and waited on nothing: for a server answering warm queries on
  // its network thread. REQUIRES: ValidateQuery(world, rect) is ok. nullopt
  // for a layered world.
  std::optional<std::vector<RegionHandle>> CachedRegions(const World& world, const Rect& rect);

  // How many of the world's points lie in the rectangle. Same cost and errors.
  StatusOr<int64_t> Count(const World& world, const Rect& rect);

  // One whole region, shared (no copy). OUT_OF_RANGE beyond the precision
  // range; INVALID_ARGUMENT for a layered world (ask its layers' worlds).
  StatusOr<RegionHandle> Region(const World& world, RegionKey key);

  // The checks Points applies (CheckQueryRect under max_query_area), for
  // callers that validate at the edge.
  Status ValidateQuery(const World& world, const Rect& rect) const;

  RegionCacheStats CacheStats() const { return cache_.Stats(); }
  const PlaneEngineOptions& options() const { return options_; }

 private:
  // Generated regions for `wanted` (all of them, in `wanted`'s order),
  // generating missing ones and their lower-ranked dependencies, each as soon
  // as its own dependencies are generated.
  std::vector<RegionHandle> Resolve(const World& world, const std::vector<RegionKey>& wanted);
  static std::vector<RegionKey> RegionsOverlapping(const World& world, const Rect& rect);

  PlaneEngineOptions options_;
  RegionCache cache_;
  std::unique_ptr<boost::asio::thread_pool> pool_;
  // A region run's working memory, reused by the next run on any thread:
  // about 200 kB each for A3, outside the cache's budget.
  ScratchPool<RegionScratch> scratch_;
};

// The sides of `rect` that cut into a region owning `owned` (bit 0: x0, 1: x1,
// 2: y0, 3: y1): a region's points lie in what it owns, so only these sides
// can leave one of them outside. 0 for a region wholly inside.
inline int CuttingSides(const Rect& rect, const Rect& owned) {
  return (owned.x0 < rect.x0 ? 1 : 0) | (rect.x1 < owned.x1 ? 2 : 0) |
         (owned.y0 < rect.y0 ? 4 : 0) | (rect.y1 < owned.y1 ? 8 : 0);
}

// 1 if p lies inside `rect` on its sides kSides (CuttingSides' bits; the
// others are not tested), else 0, without a branch: each test a 0 or 1,
// combined by `&`.
template <int kSides>
size_t InsideOnSides(const Rect& rect, Vec2 p) {
  size_t inside = 1;
  if constexpr ((kSides & 1) != 0) inside &= static_cast<size_t>(rect.x0 <= p.x);
  if constexpr ((kSides & 2) != 0) inside &= static_cast<size_t>(p.x < rect.x1);
  if constexpr ((kSides & 4) != 0) inside &= static_cast<size_t>(rect.y0 <= p.y);
  if constexpr ((kSides & 8) != 0) inside &= static_cast<size_t>(p.y < rect.y1);
  return inside;
}

// f(std::integral_constant<int, sides>{}) for `sides` in [0, 16) (CuttingSides),
// returning its count: code made for the sides that cut, chosen once a region.
template <typename F>
size_t WithCuttingSides(int sides, F f) {
  size_t result = 0;
  [&]<int... kSides>(std::integer_sequence<int, kSides...>) {
    (void)((sides == kSides && (result = f(std::integral_constant<int, kSides>{}), true)) || ...);
  }
  (std::make_integer_sequence<int, 16>{});
  return result;
}

// VisitPointsInside for a region that the sides kSides (CuttingSides) of
// `rect` cut: only those sides are tested. A rectangle's edge crosses most
// of the regions it cuts on one side only, so a point costs one comparison
// there instead of four.
template <int kSides, typename Visit>
size_t VisitPointsInsideOf(const std::vector<Vec2>& points, const Rect& rect, uint64_t first_id,
                           Visit& visit) {
  // Indices kept, a chunk at a time, then visited: a loop without data-dependent branches.
  constexpr size_t kChunk = 256;
  uint32_t kept[kChunk];
  size_t total = 0;
  for (size_t start = 0; start < points.size(); start += kChunk) {
    const size_t stop = std::min(points.size(), start + kChunk);
    size_t count = 0;
    for (size_t k = start; k < stop; ++k) {
      kept[count] = static_cast<uint32_t>(k);
      count += InsideOnSides<kSides>(rect, points[k]);
    }
    for (size_t n = 0; n < count; ++n) visit(points[kept[n]], first_id + kept[n]);
    total += count;
  }
  return total;
}

// Calls visit(points[k], first_id + k) for the points of `points`, a region
// owning `owned`, that lie in `rect`, in order; returns how many. The test
// has no branch: whether a point of a region the rectangle cuts lies inside
// follows no pattern, and mispredicting it was most of a warm tile's copy
// (docs/performance.md).
template <typename Visit>
size_t VisitPointsInside(const std::vector<Vec2>& points, const Rect& rect, const Rect& owned,
                         uint64_t first_id, Visit& visit) {
  // Sides 0, a region wholly inside, tests nothing.
  return WithCuttingSides(CuttingSides(rect, owned), [&](auto sides) {
    return VisitPointsInsideOf<decltype(sides)::value>(points, rect, first_id, visit);
  });
}

// Calls visit(position, id) for the points of `regions` (Regions or
// CachedRegions of the same world and rect) that lie in `rect`, in query
// order, skipping the first `begin` and stopping before index `end`; returns
// how many lie in `rect` in all. Regions wholly inside are counted, not tested.
// A `visit` that may also be called as visit(points, count, first_id) gets
// the points it takes of a region wholly inside in one such call (points
// [0, count), their ids first_id + k), which a writer can copy in bulk. One
// that may be called as visit(points, count, first_id, rect, sides) gets a
// region that `rect` cuts (on the sides `sides`, CuttingSides) and whose
// points inside it all take, in one such call, and returns how many it kept:
// those of points [0, count) inside `rect`, in order.
template <typename Visit>
size_t VisitPoints(const std::vector<RegionHandle>& regions, const RegionLayout& layout,
                   const Rect& rect, size_t begin, size_t end, Visit visit) {
  size_t index = 0;  // of the next point inside, in query order
  for (const RegionHandle& region : regions) {
    const std::vector<Vec2>& points = region->points;
    const Rect owned = layout.RegionRect(region->key);
    // Ids of one region are consecutive: the index sits in the low bits.
    const uint64_t first_id = EncodePointId(region->key, 0, layout.point_id_index_bits());
    if (rect.x0 <= owned.x0 && owned.x1 <= rect.x1 && rect.y0 <= owned.y0 && owned.y1 <= rect.y1) {
      const size_t from = std::max(begin, index) - index;
      const size_t to = std::min(points.size(), end > index ? end - index : 0);
      if constexpr (std::is_invocable_v<Visit&, const Vec2*, size_t, uint64_t>) {
        if (from < to) visit(points.data() + from, to - from, first_id + from);
      } else {
        for (size_t k = from; k < to; ++k) visit(points[k], first_id + k);
      }
      index += points.size();
      continue;
    }
    // The page takes every point of this region inside (the usual case).
    if (index >= begin && end >= index && end - index >= points.size()) {
      if constexpr (std::is_invocable_r_v<size_t, Visit&, const Vec2*, size_t, uint64_t,
                                          const Rect&, int>) {
        index += visit(points.data(), points.size(), first_id, rect, CuttingSides(rect, owned));
      } else {
        index += VisitPointsInside(points, rect, owned, first_id, visit);
      }
      continue;
    }
    for (size_t k = 0; k < points.size(); ++k) {
      if (!rect.Contains(points[k])) continue;
      if (index >= begin && index < end) visit(points[k], first_id + k);
      ++index;
    }
  }
  return index;
}

}  // namespace scallop
