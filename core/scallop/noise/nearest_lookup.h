// NearestLookup: the cellular-noise basis of a world at any positions: the
// nearest point's id and position, F1, F2 and the cell value, exact and
// deterministic. Keeps a byte-bounded cache of per-region search grids on
// top of a PlaneEngine. Thread-safe: one lookup serves every request.
#pragma once

#include <cstdint>
#include <functional>
#include <list>
#include <memory>
#include <mutex>
#include <span>
#include <unordered_map>
#include <vector>

#include "scallop/base/scratch_pool.h"
#include "scallop/base/status.h"
#include "scallop/noise/field_nearest_grid.h"
#include "scallop/noise/nearest_point.h"
#include "scallop/noise/nearest_search_grid.h"
#include "scallop/plane/plane_engine.h"

namespace scallop {

enum class NearestMethod {
  kGrid,        // per-region search grids, falling back to kBruteForce when uncertified
  kBruteForce,  // every point of growing squares about the position: slow, obviously right
};

struct NearestLookupOptions {
  // Budget of the search-grid cache (about 19 KB a region: 64 MB holds 3,300;
  // a field world's grid holds its region and margin, about 24 bytes a point).
  int64_t cache_bytes = int64_t{64} << 20;
  NearestMethod method = NearestMethod::kGrid;
  // The grids' vector width (same answers either way): kTwoLanes runs the
  // SSE2 code a CPU without AVX2 gets, for nearest_bench to measure that.
  NearestSearchGrid::FirstPassWidth first_pass_width = NearestSearchGrid::FirstPassWidth::kWidest;
};

// Polled during long calls; true asks the call to stop with kCancelled (a
// server passes its client's cancellation and deadline). Null: never stops.
using StopRequested = std::function<bool()>;

struct NearestLookupStats {
  int64_t lookups = 0;       // positions answered
  int64_t fallbacks = 0;     // of which by kBruteForce because a grid could not certify
  int64_t grids_built = 0;   // cache misses
  int64_t grids_cached = 0;  // grids stored now
  int64_t bytes = 0;         // their bytes
};

class NearestLookup {
 public:
  // `engine` must outlive the lookup; its region cache supplies the points.
  explicit NearestLookup(PlaneEngine& engine, NearestLookupOptions options = {});
  ~NearestLookup();
  NearestLookup(const NearestLookup&) = delete;
  NearestLookup& operator=(const NearestLookup&) = delete;

  // The basis at each position: results[k] answers positions[k]. Nothing is
  // written unless every position is valid.
  // Rejects: INVALID_ARGUMENT for a
  // non-finite coordinate; OUT_OF_RANGE for |x| or |y| > 2^32 d; errors name
  // the position, e.g. "positions[3].x".
  // Cost, warm: 29 to 46 ns of CPU a position on this project's shared
  // Intel Xeon at load 2 to 6 (21.6 to 35.0M/s at random positions,
  // docs/performance.md; Zen 3 unmeasured since it was slower, docs/noise.md), plus a
  // mutex and a hash lookup per region a batch visits. A missing grid costs
  // one PlaneEngine::Points query of 24 d x 24 d, plus generation when cold.
  // Memory: about 28 bytes a position besides `results`, to group by region;
  // kept for later calls (up to 8 calls' worth, batches up to 2^20).
  // Scattered positions cost a grid each (milliseconds when cold), so the
  // cost is bounded by the distinct regions the positions lie in, not by
  // their number: callers bound those. `stop` is polled before every grid
  // is built or read and before brute-force answers, so an abandoned call
  // ends within one grid's work with kCancelled (results then unspecified).
  // A radius-field world is answered the same way, exactly, from grids of
  // FieldNearestGrid (its regions are 6 r_max; a missing grid costs the
  // 3 x 3 regions about it). Where a grid cannot certify (only near masks)
  // the brute force reads squares of half side 4 r_max up to 32 r_max
  // (FieldFallbackReach); a position with fewer than two points within that
  // (deep inside a mask) is OUT_OF_RANGE, naming it.
  Status Nearest(const World& world, std::span<const Vec2> positions,
                 std::span<NearestPoint> results, const StopRequested& stop = nullptr);

  // The checks Nearest applies to one position; `index` names it in the message.
  static Status ValidatePosition(const World& world, Vec2 position, size_t index);

  // How many distinct regions (RegionLayout(world)) the positions lie in:
  // what bounds Nearest's cost. O(n log n), about 28 bytes a position.
  // REQUIRES: every position passes ValidatePosition.
  static int64_t CountRegions(const World& world, std::span<const Vec2> positions);

  // How far the brute force looks about a position, as a half side: 32 d, or
  // 32 r_max on a radius-field world. Beyond it a position is not answered
  // (INTERNAL on a constant world, which is maximal; OUT_OF_RANGE on a field
  // world, where a mask may leave it that far from any point). What a call
  // may read beyond its positions' regions (server/request_cost.cc).
  static double FallbackReach(const World& world);

  NearestLookupStats Stats() const;

 private:
  // One region's search grid: a constant world's or a field world's.
  struct GridHandle {
    std::shared_ptr<const NearestSearchGrid> constant;
    std::shared_ptr<const FieldNearestGrid> field;
    size_t Bytes() const { return field ? field->Bytes() : constant->Bytes(); }
  };
  struct Key {
    World world;
    RegionKey region;
    friend bool operator==(const Key&, const Key&) = default;
  };
  struct KeyHash {
    size_t operator()(const Key& key) const;
  };
  struct Entry {
    GridHandle grid;
    std::list<Key>::iterator lru;
  };

  struct Scratch;  // per-call buffers (.cc)

  // The grid each position is answered by: grids[grid_of[k]] for position k
  // (grid_of may be longer than positions; the rest is unspecified), and
  // counts[g + 1] positions for grid g (counts[0] = 0). Validates each
  // position before its grid is fetched (ValidatePosition's errors).
  Status AssignGrids(const World& world, std::span<const Vec2> positions,
                     std::vector<GridHandle>& grids, std::vector<uint32_t>& grid_of,
                     std::vector<uint32_t>& counts, const StopRequested& stop);
  // The grid of `region`, from the cache or built (outside the mutex: two
  // threads may build the same grid at once, and both get identical grids).
  StatusOr<GridHandle> Grid(const World& world, RegionKey region);
  // Exact answer from the engine's points in squares of growing side about p.
  StatusOr<TwoNearest> BruteForce(const World& world, Vec2 p);
  // Every world point in `rect` (within the precision range), with its id, in
  // query order: one engine query when the engine's area limit allows, else
  // region by region, so a field world's wide squares are never refused.
  Status CollectPoints(const World& world, const Rect& rect, PlanePoints& points);

  PlaneEngine& engine_;
  const NearestLookupOptions options_;
  mutable std::mutex mutex_;
  std::unordered_map<Key, Entry, KeyHash> grids_;  // looked up only: order never reaches output
  std::list<Key> lru_;                             // front: most recently used
  NearestLookupStats stats_;
  ScratchPool<Scratch> scratch_;
};

}  // namespace scallop
