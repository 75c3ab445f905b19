// ViewportTracker: validation of viewport updates, the kept range of regions,
// the per-region bitsets of points sent, and the prefetch prediction.
#include "scallop/plane/viewport_tracker.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "scallop/base/number_text.h"
#include "scallop/plane/point_id.h"
#include "scallop/plane/query_rect.h"

namespace scallop {
Status ValidateViewportUpdate(const World& world, const ViewportUpdate& update, double max_area) {
  if (Status status = CheckRectBounds(world, update.viewport, "viewport"); !status.ok()) {
    return status;
  }
  if (!std::isfinite(update.velocity.x)) return InvalidArgument("velocity_x: must be finite");
  if (!std::isfinite(update.velocity.y)) return InvalidArgument("velocity_y: must be finite");
  if (!(std::isfinite(update.keep_margin) && update.keep_margin >= 0)) {
    return InvalidArgument("keep_margin: must be finite and >= 0, got " +
                           NumberText(update.keep_margin));
  }
  // What the call keeps, and so reads, is the viewport grown by the margin.
  return CheckQueryCost(world, Grown(update.viewport, update.keep_margin),
                        {.max_area = max_area, .name = "max_follow_area"},
                        "viewport grown by keep_margin");
}

std::vector<RegionKey> ViewportTracker::Update(const ViewportUpdate& update) {
  kept_ = RegionsOverlapping(layout_, Grown(update.viewport, update.keep_margin));
  auto kept = [&](RegionKey key) { return kept_.Contains(key); };
  std::vector<RegionKey> evicted;
  for (auto it = sent_.begin(); it != sent_.end();) {
    if (kept(it->first)) {
      ++it;
    } else {
      evicted.push_back(it->first);
      it = sent_.erase(it);
    }
  }
  for (const RegionKey& key : update.held_regions) {
    if (kept(key)) sent_[key].SetAll();
  }
  return evicted;
}

StatusOr<std::vector<RegionChunk>> ViewportTracker::TakeUnsent(const PlanePoints& in_view) {
  std::vector<RegionChunk> chunks;
  const int64_t max_points = world_.radius_field() == nullptr
                                 ? kMaxPointsPerRegion
                                 : int64_t{1} << layout_.point_id_index_bits();
  SentPoints* sent = nullptr;  // the bits of region `current`
  RegionKey current;
  for (size_t n = 0; n < in_view.ids.size(); ++n) {
    const Vec2 position = in_view.positions[n];
    const DecodedPointId id = DecodePointId(
        in_view.ids[n], layout_.RegionOf(position.x, position.y), layout_.point_id_index_bits());
    if (id.index >= max_points) {
      return Status(StatusCode::kInternal, "region (" + std::to_string(id.region.i) + ", " +
                                               std::to_string(id.region.j) + "): point index " +
                                               std::to_string(id.index) + " exceeds " +
                                               std::to_string(max_points));
    }
    // Points come grouped by region, so one map lookup per region suffices.
    if (sent == nullptr || id.region != current) {
      sent = &sent_[id.region];
      current = id.region;
    }
    if (sent->Test(id.index)) continue;
    sent->Set(id.index);
    if (chunks.empty() || chunks.back().key != id.region) chunks.push_back({id.region, {}});
    chunks.back().points.positions.push_back(position);
    chunks.back().points.ids.push_back(in_view.ids[n]);
  }
  return chunks;
}

std::vector<RegionKey> ViewportTracker::HeldRegions() const {
  std::vector<RegionKey> keys;
  keys.reserve(sent_.size());
  for (const auto& [key, sent] : sent_) {
    if (sent.Any()) keys.push_back(key);
  }
  return keys;
}

std::optional<Rect> ViewportTracker::PrefetchArea(const ViewportUpdate& update) const {
  if (update.velocity.x == 0 && update.velocity.y == 0) return std::nullopt;
  const Rect& view = update.viewport;
  const double dx = std::clamp(update.velocity.x * kPrefetchSeconds, -view.Width(), view.Width());
  const double dy = std::clamp(update.velocity.y * kPrefetchSeconds, -view.Height(), view.Height());
  const double limit = layout_.precision_limit();
  const Rect ahead{std::max(view.x0 + dx, -limit), std::max(view.y0 + dy, -limit),
                   std::min(view.x1 + dx, limit), std::min(view.y1 + dy, limit)};
  if (!(ahead.x0 < ahead.x1 && ahead.y0 < ahead.y1)) return std::nullopt;
  return ahead;
}

}  // namespace scallop
