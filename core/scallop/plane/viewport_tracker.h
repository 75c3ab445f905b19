// ViewportTracker: what one follower of a moving viewport already holds, so a
// stream sends each point once while its region stays kept and tells the
// follower which regions to drop. Pure bookkeeping (no generation, no gRPC):
// the server's Follow call drives it, and tests drive it directly.
#pragma once

#include <algorithm>
#include <map>
#include <optional>
#include <vector>

#include "scallop/base/status.h"
#include "scallop/geometry/rect.h"
#include "scallop/geometry/vec2.h"
#include "scallop/plane/plane_engine.h"
#include "scallop/plane/query_rect.h"
#include "scallop/plane/region_layout.h"
#include "scallop/plane/world.h"

namespace scallop {

// A 16 d square holds at most 296 points d apart (the hexagonal packing
// bound), so a constant world's point indices are below 296. A field world's
// are below 2^point_id_index_bits (region_layout.h).
inline constexpr int kMaxPointsPerRegion = 296;

// One viewport update, as the follower states it.
struct ViewportUpdate {
  Rect viewport{};                        // half-open, what the follower shows now
  Vec2 velocity{};                        // world units per second; (0, 0): not moving
  double keep_margin = 0.0;               // regions touching the viewport grown by this are kept
  std::vector<RegionKey> held_regions{};  // regions the follower holds whole already
};

// Seconds of motion the prefetch looks ahead, and its cap: the predicted
// viewport is moved by velocity * kPrefetchSeconds, but at most one viewport
// width (height) on each axis, so it always touches the current one (no
// unprefetched gap in between) and a wrong guess wastes one viewport of work.
inline constexpr double kPrefetchSeconds = 1.0;

// Checks an update of `world`: the viewport's bounds, then the viewport
// grown by keep_margin against max_area d^2 and the regions it crosses (the
// rectangle rule of query_rect.h, whose limits every query obeys). Errors name the field:
// INVALID_ARGUMENT "viewport.x0: must be finite", "viewport: x0 must be less
// than x1", "velocity_x: must be finite", "keep_margin: must be finite and
// >= 0", "viewport grown by keep_margin: area is ... (max_follow_area)";
// OUT_OF_RANGE "viewport.y1: |value| must be at most 2^32 * min_distance".
// O(1).
Status ValidateViewportUpdate(const World& world, const ViewportUpdate& update, double max_area);

// The part of one region's points newly sent to the follower.
struct RegionChunk {
  RegionKey key;
  PlanePoints points;  // in the region's point order (point_id.h)
};

// Not thread-safe: one tracker per follower, used by one update at a time.
class ViewportTracker {
 public:
  explicit ViewportTracker(const World& world) : world_(world), layout_(world) {}

  // Moves to `update`: every region held before and no longer kept (not
  // touching the viewport grown by keep_margin) is forgotten and returned,
  // in (i, j) order, for the follower to evict; the kept regions named in
  // held_regions are marked as wholly sent (held regions not kept are
  // ignored: the follower may drop them itself). The update must have
  // passed ValidateViewportUpdate. Cost: O(regions held + held_regions,
  // times log of the regions held).
  std::vector<RegionKey> Update(const ViewportUpdate& update);

  // The points of `in_view` not sent yet, grouped by region in the order
  // they come (PlaneEngine::Points order: regions by row, then column), and
  // marked as sent. `in_view` must be the world's points in the viewport of
  // the last Update (PlaneEngine::Points(world, viewport)). INTERNAL when a
  // point index exceeds kMaxPointsPerRegion, or for a field world
  // 2^point_id_index_bits (a broken generator). O(points).
  StatusOr<std::vector<RegionChunk>> TakeUnsent(const PlanePoints& in_view);

  // Regions whose points the follower holds (in whole or in part), in (i, j) order.
  std::vector<RegionKey> HeldRegions() const;

  // Where to generate ahead of `update`'s motion: the viewport moved by
  // velocity * kPrefetchSeconds (capped, see above), clipped to the
  // precision range. None when the update is not moving or the prediction
  // lies wholly outside the range. O(1).
  std::optional<Rect> PrefetchArea(const ViewportUpdate& update) const;

 private:
  // The indices of one region's points sent so far, one bit each, grown as
  // indices come (a field world's region may hold 2^18 points, most never in
  // view); or all of them, for a region the follower holds whole.
  class SentPoints {
   public:
    void SetAll() {
      all_ = true;
      words_.clear();
    }
    void Set(uint32_t index) {
      if (all_) return;
      if (index / 64 >= words_.size()) words_.resize(index / 64 + 1);
      words_[index / 64] |= uint64_t{1} << (index % 64);
    }
    bool Test(uint32_t index) const {
      return all_ || (index / 64 < words_.size() && ((words_[index / 64] >> (index % 64)) & 1));
    }
    bool Any() const {
      return all_ || std::any_of(words_.begin(), words_.end(), [](uint64_t w) { return w != 0; });
    }

   private:
    bool all_ = false;
    std::vector<uint64_t> words_;
  };

  World world_;
  RegionLayout layout_;
  RegionRange kept_;                      // the regions kept
  std::map<RegionKey, SentPoints> sent_;  // ordered, so evictions come in a fixed order
};

}  // namespace scallop
