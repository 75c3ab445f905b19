// ViewportTracker: validation of viewport updates, the kept range of regions,
// the per-region bitsets of points sent, and the prefetch prediction.
#include "scallop/plane/viewport_tracker.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <tuple>

#include "scallop/plane/point_id.h"

namespace scallop {
namespace {

// "4e+06", "15641": shortest readable text, unlike std::to_string's six decimals.
std::string Number(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

// The lowest and highest region a valid half-open rectangle overlaps: it
// ends just below x1 and y1.
std::pair<RegionKey, RegionKey> RegionRange(const RegionLayout& layout, const Rect& rect) {
  return {layout.RegionOf(rect.x0, rect.y0),
          layout.RegionOf(std::nextafter(rect.x1, rect.x0), std::nextafter(rect.y1, rect.y0))};
}

}  // namespace

Status ValidateViewportUpdate(const World& world, const ViewportUpdate& update, double max_area) {
  const Rect& view = update.viewport;
  const double limit = RegionLayout(world.min_distance).precision_limit();
  const std::pair<const char*, double> corners[] = {{"viewport.x0", view.x0},
                                                    {"viewport.y0", view.y0},
                                                    {"viewport.x1", view.x1},
                                                    {"viewport.y1", view.y1}};
  for (const auto& [field, value] : corners) {
    if (!std::isfinite(value)) return InvalidArgument(std::string(field) + ": must be finite");
    if (std::abs(value) > limit) {
      return OutOfRange(std::string(field) +
                        ": |value| must be at most 2^32 * min_distance = " + Number(limit));
    }
  }
  if (!(view.x0 < view.x1)) return InvalidArgument("viewport: x0 must be less than x1");
  if (!(view.y0 < view.y1)) return InvalidArgument("viewport: y0 must be less than y1");
  if (!std::isfinite(update.velocity.x)) return InvalidArgument("velocity_x: must be finite");
  if (!std::isfinite(update.velocity.y)) return InvalidArgument("velocity_y: must be finite");
  if (!(std::isfinite(update.keep_margin) && update.keep_margin >= 0)) {
    return InvalidArgument("keep_margin: must be finite and >= 0, got " +
                           Number(update.keep_margin));
  }
  const double d = world.min_distance;
  const Rect kept = Grown(view, update.keep_margin);
  // An overflowing margin makes the area infinite, which fails here too.
  const double area = kept.Width() / d * (kept.Height() / d);
  if (!(area <= max_area)) {
    return InvalidArgument("viewport grown by keep_margin: area is " + Number(area) +
                           " min_distance^2, must be at most " + Number(max_area) +
                           " (max_follow_area)");
  }
  // As for every rectangle query: a thin viewport of tiny area could
  // otherwise cross millions of regions.
  const auto [low, high] = RegionRange(RegionLayout(d), kept);
  const double regions =
      (static_cast<double>(high.i - low.i) + 1) * (static_cast<double>(high.j - low.j) + 1);
  if (const double max_regions = max_area / 64 + 16; regions > max_regions) {
    return InvalidArgument("viewport grown by keep_margin: crosses " + Number(regions) +
                           " regions of 16 min_distance, at most " + Number(max_regions) +
                           " (max_follow_area / 64 + 16)");
  }
  return Status::Ok();
}

std::vector<RegionKey> ViewportTracker::Update(const ViewportUpdate& update) {
  std::tie(keep_low_, keep_high_) =
      RegionRange(layout_, Grown(update.viewport, update.keep_margin));
  auto kept = [&](RegionKey key) {
    return keep_low_.i <= key.i && key.i <= keep_high_.i && keep_low_.j <= key.j &&
           key.j <= keep_high_.j;
  };
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
    if (kept(key)) sent_[key].set();
  }
  return evicted;
}

StatusOr<std::vector<RegionChunk>> ViewportTracker::TakeUnsent(const PlanePoints& in_view) {
  std::vector<RegionChunk> chunks;
  SentPoints* sent = nullptr;  // the bits of region `current`
  RegionKey current;
  for (size_t n = 0; n < in_view.ids.size(); ++n) {
    const Vec2 position = in_view.positions[n];
    const DecodedPointId id =
        DecodePointId(in_view.ids[n], layout_.RegionOf(position.x, position.y));
    if (id.index >= kMaxPointsPerRegion) {
      return Status(StatusCode::kInternal, "region (" + std::to_string(id.region.i) + ", " +
                                               std::to_string(id.region.j) + "): point index " +
                                               std::to_string(id.index) + " exceeds " +
                                               std::to_string(kMaxPointsPerRegion));
    }
    // Points come grouped by region, so one map lookup per region suffices.
    if (sent == nullptr || id.region != current) {
      sent = &sent_[id.region];
      current = id.region;
    }
    if (sent->test(id.index)) continue;
    sent->set(id.index);
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
    if (sent.any()) keys.push_back(key);
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
