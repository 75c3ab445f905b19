// NearestLookup: validation, the per-call table of grids (so a batch takes
// the cache's mutex once per region it visits, not once per position), the
// shared grid cache and the brute-force fallback.
#include "scallop/noise/nearest_lookup.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>

#include "scallop/base/number_text.h"
#include "scallop/noise/coordinate_pair.h"
#include "scallop/plane/query_rect.h"
#include "scallop/random/rng.h"

namespace scallop {
namespace {

// floor(v) as an integer, for |v| < 2^62, without a library call (x86-64
// without SSE4.1 has no floor instruction).
int64_t FloorToInt64(double v) {
  const auto truncated = static_cast<int64_t>(v);
  return truncated - (v < static_cast<double>(truncated) ? 1 : 0);
}

// The region of p by multiplication (inverse_side = 1 / S, rounded), kept
// inside the precision range's regions. Rounding can move a position within
// 2^-24 S of a seam to the neighbouring region; that is harmless where any
// grid holding p's 3x3 block will do, since every grid reaches 3 d past its
// region (a field world's, 2.25 r_max).
RegionKey ApproximateRegionOf(Vec2 p, double inverse_side, int64_t regions_per_half_axis) {
  // A position exactly on the high limit belongs to no region inside the
  // range (regions_per_half_axis); its last region's grid reaches beyond it,
  // so that grid answers it.
  const int64_t n = regions_per_half_axis;
  return {std::clamp(FloorToInt64(p.x * inverse_side), -n, n - 1),
          std::clamp(FloorToInt64(p.y * inverse_side), -n, n - 1)};
}

// `rect` cut to the precision range, where the world has its points.
Rect ClipToRange(Rect rect, double limit) {
  return {std::max(rect.x0, -limit), std::max(rect.y0, -limit), std::min(rect.x1, limit),
          std::min(rect.y1, limit)};
}

// Open-addressed table of the grids one call has used, so that a batch takes
// the shared cache's mutex once per region it visits rather than once per
// position. Up to 1024 slots (every region of a 512 d square), fewer for
// small batches, whose table would cost more to clear than it saves. Linear
// probing up to kMaxProbes slots: a direct-mapped table sent every position
// of two colliding regions back to the shared cache, a quarter of random
// positions with 256 regions in 1024 slots.
constexpr size_t kMaxCallSlots = 1024;
constexpr size_t kMaxProbes = 16;

// The dense window: kWindowSide^2 regions (a 1,024 d square) centred on the
// first position's region, for batches of at least kWindowMinPositions,
// which amortise clearing its 16 KB.
constexpr int64_t kWindowSide = 64;
constexpr size_t kWindowMinPositions = 1024;
constexpr uint32_t kNoGrid = ~uint32_t{0};
// The bits of a pair of int32 cells, each xor-ed with kWindowSide, that are
// all clear exactly when both cells are in [kWindowSide, 2 kWindowSide).
constexpr uint64_t kOutsideWindowCells = ~((uint64_t{kWindowSide - 1} << 32) | (kWindowSide - 1));

// Whether region `key` has a region of the precision range on every side. Only
// such regions enter the window, whose loop then need not test the range: a
// position it sends to one is at least 16 d inside the range (rounding in
// its cell is far below that), and positions beyond the range (or NaN) fall
// in edge regions or outside the window, and so are validated one by one.
bool InnerRegion(RegionKey key, int64_t regions_per_half_axis) {
  const int64_t n = regions_per_half_axis;
  return key.i > -n && key.i < n - 1 && key.j > -n && key.j < n - 1;
}

size_t CallSlotCount(size_t positions) {
  return std::min(kMaxCallSlots, std::bit_ceil(std::max<size_t>(positions, 1)));
}

size_t CallSlotOf(RegionKey key, size_t slot_count) {
  return static_cast<size_t>(
      Mix64(static_cast<uint64_t>(key.i) * 0x9e3779b97f4a7c15ULL ^ static_cast<uint64_t>(key.j)) &
      (slot_count - 1));
}

// How far ahead of its write a grouped entry's line is prefetched, in
// entries: 4 entries (96 bytes) reach past the line being written.
constexpr uint32_t kScatterAhead = 4;

// Brute-force answers between polls of the caller's stop: each is an engine
// query, so a stop waits for at most this many of them.
constexpr size_t kAnswersPerStopPoll = 64;

// ValidatePosition's test, inline: the call only to name a bad position.
bool InRange(Vec2 p, double limit) { return std::abs(p.x) <= limit && std::abs(p.y) <= limit; }

Status StopStatus() {
  return Cancelled("nearest: stopped by the caller (cancelled or past deadline)");
}

bool StopNow(const StopRequested& stop) { return stop && stop(); }

}  // namespace

size_t NearestLookup::KeyHash::operator()(const Key& key) const {
  return static_cast<size_t>(
      HashWords({key.world.fingerprint(), static_cast<uint64_t>(key.region.i),
                 static_cast<uint64_t>(key.region.j)}));
}

// Buffers of one call, kept for the next: a batch's worth of them is about
// 28 bytes a position, and fresh memory for each call cost a page fault
// every 4 KB (and the clearing of every entry).
struct NearestLookup::Scratch {
  std::vector<uint32_t> grid_of;        // the grid of each position
  std::vector<uint32_t> starts;         // first sorted entry of each grid, then the end
  std::vector<IndexedPosition> sorted;  // positions by grid; only a prefix is in use
  std::vector<uint32_t> refused;        // of one grid's entries, those it did not certify
};

// Scratch kept for reuse: enough for a few concurrent calls of the default
// batch limit, not a copy of every large batch ever seen.
constexpr size_t kMaxSpareScratch = 8;
constexpr size_t kMaxScratchPositions = size_t{1} << 20;

NearestLookup::NearestLookup(PlaneEngine& engine, NearestLookupOptions options)
    : engine_(engine), options_(options), scratch_(kMaxSpareScratch) {}

NearestLookup::~NearestLookup() = default;

Status NearestLookup::ValidatePosition(const World& world, Vec2 position, size_t index) {
  const double limit = RegionLayout(world).precision_limit();
  // The message is built only on failure: this runs once per position.
  if (InRange(position, limit)) return Status::Ok();
  const std::pair<char, double> coordinates[] = {{'x', position.x}, {'y', position.y}};
  for (const auto& [axis, value] : coordinates) {
    const std::string field = "positions[" + std::to_string(index) + "]." + axis;
    if (!std::isfinite(value)) return InvalidArgument(field + ": must be finite");
    if (std::abs(value) > limit) {
      return OutOfRange(field +
                        ": |value| must be at most 2^32 * min_distance = " + NumberText(limit));
    }
  }
  return Status::Ok();
}

int64_t NearestLookup::CountRegions(const World& world, std::span<const Vec2> positions) {
  const RegionLayout layout(world);
  std::vector<RegionKey> keys;
  keys.reserve(positions.size());
  for (const Vec2& p : positions) keys.push_back(layout.RegionOf(p.x, p.y));
  std::sort(keys.begin(), keys.end());
  return std::unique(keys.begin(), keys.end()) - keys.begin();
}

Status NearestLookup::Nearest(const World& world, std::span<const Vec2> positions,
                              std::span<NearestPoint> results, const StopRequested& stop) {
  if (results.size() != positions.size()) {
    return InvalidArgument("results: must have one entry per position");
  }
  // A layered world's basis is per layer, each layer a world of its own (its points and ids).
  if (world.layers() != nullptr) {
    return InvalidArgument(
        "world.layers: the noise basis is a layer's; ask for one layer (its world, "
        "WorldLayers::world)");
  }
  int64_t fallbacks = 0;
  // The exact answer at p from the engine's points, when no grid certifies one.
  auto answer_by_brute_force = [&](size_t k, Vec2 p) -> Status {
    StatusOr<TwoNearest> exact = BruteForce(world, p);
    if (exact.status().code() == StatusCode::kOutOfRange) {
      return OutOfRange("positions[" + std::to_string(k) + "]: " + exact.status().message());
    }
    if (!exact.ok()) return exact.status();
    results[k] = ToNearestPoint(*exact);
    return Status::Ok();
  };
  if (options_.method == NearestMethod::kBruteForce) {
    const double limit = RegionLayout(world).precision_limit();
    for (size_t k = 0; k < positions.size(); ++k) {
      if (!InRange(positions[k], limit)) return ValidatePosition(world, positions[k], k);
    }
    for (size_t k = 0; k < positions.size(); ++k) {
      if (k % kAnswersPerStopPoll == 0 && StopNow(stop)) return StopStatus();
      if (Status status = answer_by_brute_force(k, positions[k]); !status.ok()) return status;
    }
  } else {
    std::unique_ptr<Scratch> scratch = scratch_.Take();
    std::vector<GridHandle> grids;
    std::vector<uint32_t>& starts = scratch->starts;
    if (Status status = AssignGrids(world, positions, grids, scratch->grid_of, starts, stop);
        !status.ok()) {
      return status;
    }
    // Positions grouped by grid (a counting sort, stable), so each grid is
    // read from memory once per batch rather than once per position. The
    // positions are copied in that order: reading them through the
    // permutation would miss the cache on every one.
    // (Plain pointers: through the vectors GCC reloaded them on every entry.)
    const uint32_t* grid_of = scratch->grid_of.data();
    for (size_t g = 0; g < grids.size(); ++g) starts[g + 1] += starts[g];
    // The entries go to as many places at once as there are grids (256 in
    // a 256 d square), more streams than the hardware prefetcher follows,
    // so each write asks for the line its grid's entries reach next: that
    // grid's next entry comes a few hundred positions later, by when the
    // line is in the cache (docs/noise.md, "Speed").
    if (scratch->sorted.size() < positions.size() + kScatterAhead) {
      scratch->sorted.resize(positions.size() + kScatterAhead);
    }
    IndexedPosition* sorted = scratch->sorted.data();
    std::vector<uint32_t> next_vector(starts.begin(), starts.end() - 1);
    uint32_t* next = next_vector.data();
    for (size_t k = 0; k < positions.size(); ++k) {
      const uint32_t slot = next[grid_of[k]]++;
      __builtin_prefetch(sorted + slot + kScatterAhead, 1);
      // Field by field: as one aggregate GCC 12 passed it through the stack,
      // and reloading the index from there cost more than the rest of the loop.
      IndexedPosition& entry = sorted[slot];
      entry.position = positions[k];
      entry.index = static_cast<uint32_t>(k);
    }
    // The brute force for sorted entry j, which no grid could certify.
    auto fall_back = [&](uint32_t j) -> Status {
      ++fallbacks;
      // A fallback queries the engine, possibly cold: poll before each.
      if (StopNow(stop)) return StopStatus();
      return answer_by_brute_force(sorted[j].index, sorted[j].position);
    };
    // The positions of grid g: a constant world's in one call (AnswerEach),
    // a field world's one by one.
    std::vector<uint32_t>& refused = scratch->refused;
    auto answer_from = [&](size_t g) -> Status {
      if (const NearestSearchGrid* grid = grids[g].constant.get()) {
        refused.clear();
        // The next group's grid is prefetched meanwhile (a hint).
        const NearestSearchGrid* next =
            g + 1 < grids.size() ? grids[g + 1].constant.get() : nullptr;
        grid->AnswerEach({sorted + starts[g], sorted + starts[g + 1]}, results, refused, next);
        for (const uint32_t offset : refused) {
          if (Status status = fall_back(starts[g] + offset); !status.ok()) return status;
        }
        return Status::Ok();
      }
      for (uint32_t j = starts[g]; j < starts[g + 1]; ++j) {
        TwoNearest best;
        if (grids[g].field->FindTwoNearest(sorted[j].position, best)) {
          results[sorted[j].index] = ToNearestPoint(best);
        } else if (Status status = fall_back(j); !status.ok()) {
          return status;
        }
      }
      return Status::Ok();
    };
    for (size_t g = 0; g < grids.size(); ++g) {
      if (StopNow(stop)) return StopStatus();
      if (Status status = answer_from(g); !status.ok()) return status;
    }
    if (scratch->sorted.capacity() <= kMaxScratchPositions + kScatterAhead) {
      scratch_.Return(std::move(scratch));
    }
  }
  std::lock_guard lock(mutex_);
  stats_.lookups += static_cast<int64_t>(positions.size());
  stats_.fallbacks += fallbacks;
  return Status::Ok();
}

Status NearestLookup::AssignGrids(const World& world, std::span<const Vec2> positions,
                                  std::vector<GridHandle>& grids, std::vector<uint32_t>& grid_of,
                                  std::vector<uint32_t>& counts, const StopRequested& stop) {
  const RegionLayout layout(world);
  const double limit = layout.precision_limit();
  counts.assign(1, 0);
  const double inverse_side = 1.0 / layout.side();
  const int64_t regions_per_half_axis = layout.regions_per_half_axis();
  struct CallSlot {
    RegionKey key;
    uint32_t grid = 0;
    bool used = false;
  };
  std::vector<CallSlot> slots(CallSlotCount(positions.size()));
  // Large batches also get a dense window of regions about the first
  // position's: a region's grid there is one indexed load, no hash or probe.
  std::vector<uint32_t> window;
  RegionKey window_low;
  if (positions.size() >= kWindowMinPositions) {
    window.assign(kWindowSide * kWindowSide, kNoGrid);
    const RegionKey first = ApproximateRegionOf(positions[0], inverse_side, regions_per_half_axis);
    window_low = {first.i - kWindowSide / 2, first.j - kWindowSide / 2};
  }
  // The grid of `key` outside the window, or the first time in it.
  auto grid_by_slot = [&](RegionKey key, uint32_t& index) -> Status {
    const size_t home = CallSlotOf(key, slots.size());
    CallSlot* slot = &slots[home];
    for (size_t probe = 1; slot->used && slot->key != key && probe < kMaxProbes; ++probe) {
      slot = &slots[(home + probe) & (slots.size() - 1)];
    }
    if (!slot->used || slot->key != key) {
      // With every probed slot taken, the last is reused: a region met
      // again then gets a second entry, harmless since the grid is shared.
      // A grid may cost a cold generation: the place to notice a stop.
      if (StopNow(stop)) return StopStatus();
      StatusOr<GridHandle> grid = Grid(world, key);
      if (!grid.ok()) return grid.status();
      *slot = {key, static_cast<uint32_t>(grids.size()), true};
      grids.push_back(std::move(*grid));
      counts.push_back(0);
    }
    index = slot->grid;
    return Status::Ok();
  };
  if (grid_of.size() < positions.size()) grid_of.resize(positions.size());
  // Coherent batches (images, paths) skip the lookup while they stay in one
  // region.
  RegionKey current_key;
  uint32_t current = 0;
  uint32_t* counted = counts.data() + 1;  // moved when a grid is added
  // Plain pointers: through the vectors GCC reloaded them for every position.
  const uint32_t* const window_cells = window.empty() ? nullptr : window.data();
  uint32_t* const grid_of_data = grid_of.data();
  // One window below and to the left of it: its cells are then 64 to 127 on
  // each axis, so that truncation toward zero cannot bring a position left
  // of or below the window into it.
  const Pair window_offset_corner = {static_cast<double>(window_low.i - kWindowSide),
                                     static_cast<double>(window_low.j - kWindowSide)};
  const size_t count = positions.size();
  for (size_t k = 0; k < count; ++k) {
    // Positions in regions of the window met before, in a loop of their own
    // (with the rest in it GCC kept its constants on the stack): a region's
    // grid from one multiply and subtract and one load, both axes in a lane
    // pair, without the region's key (clamping and the comparison with the
    // current region cost more than that). Rounding may put a position
    // within an ulp of a seam into the neighbouring cell, harmless as above.
    // Validation here, not in a pass of its own: one read of the positions.
    // A window region is inner (InnerRegion), so a position found in one is
    // in range; the others are validated below. Both cells are tested in one
    // 64-bit word: 24 instructions a position, where the three lane
    // comparisons and the range test took 37.
    if (window_cells != nullptr) {
      for (; k < count; ++k) {
        const Pair w = LoadPair(positions[k]) * Broadcast2(inverse_side) - window_offset_corner;
        // Both cells in [64, 128) (NaN and far positions convert to INT32_MIN):
        // each xor-ed with 64 is then below 64, and they make the window index.
        const PairCells cells =
            __builtin_convertvector(w, PairCells) ^ static_cast<int32_t>(kWindowSide);
        if ((std::bit_cast<uint64_t>(cells) & kOutsideWindowCells) != 0) break;
        const uint32_t known = window_cells[cells[1] * kWindowSide + cells[0]];
        if (known == kNoGrid) break;
        grid_of_data[k] = known;
        ++counted[known];
      }
      if (k == count) break;
    }
    const Vec2 p = positions[k];
    if (!InRange(p, limit)) return ValidatePosition(world, p, k);
    const RegionKey key = ApproximateRegionOf(p, inverse_side, regions_per_half_axis);
    if (k == 0 || key != current_key) {
      current_key = key;
      const auto wi = static_cast<uint64_t>(key.i - window_low.i);
      const auto wj = static_cast<uint64_t>(key.j - window_low.j);
      uint32_t* in_window = !window.empty() && wi < kWindowSide && wj < kWindowSide &&
                                    InnerRegion(key, regions_per_half_axis)
                                ? &window[wj * kWindowSide + wi]
                                : nullptr;
      if (in_window != nullptr && *in_window != kNoGrid) {
        current = *in_window;
      } else {
        if (Status status = grid_by_slot(key, current); !status.ok()) return status;
        if (in_window != nullptr) *in_window = current;
        counted = counts.data() + 1;
      }
    }
    grid_of_data[k] = current;
    ++counted[current];
  }
  return Status::Ok();
}

StatusOr<NearestLookup::GridHandle> NearestLookup::Grid(const World& world, RegionKey region) {
  const Key key{world, region};
  {
    std::lock_guard lock(mutex_);
    if (auto found = grids_.find(key); found != grids_.end()) {
      lru_.splice(lru_.begin(), lru_, found->second.lru);
      return found->second.grid;
    }
  }
  const double d = world.min_distance();
  const RegionLayout layout(world);
  GridHandle grid;
  if (const RadiusField* field = world.radius_field()) {
    // The grid needs every point of its covered square (field_nearest_grid.h).
    const Rect covered = FieldNearestGrid::CoveredSquare(layout, region, field->r_max());
    PlanePoints points;
    if (Status status =
            CollectPoints(world, ClipToRange(covered, layout.precision_limit()), points);
        !status.ok()) {
      return status;
    }
    grid.field = std::make_shared<const FieldNearestGrid>(
        layout, region, field->r_min(), field->r_max(), points.positions, points.ids);
  } else {
    // The grid needs every point of its square grown by 1 d (nearest_search_grid.h).
    const Rect covered = NearestSearchGrid::CoveredSquare(d, region);
    const Rect source = ClipToRange(
        {covered.x0 - d, covered.y0 - d, covered.x1 + d, covered.y1 + d}, layout.precision_limit());
    StatusOr<PlanePoints> points = engine_.Points(world, source);
    if (!points.ok()) return points.status();
    grid.constant = std::make_shared<const NearestSearchGrid>(
        d, region, points->positions, points->ids, options_.first_pass_width);
  }

  std::lock_guard lock(mutex_);
  ++stats_.grids_built;
  auto [entry, inserted] = grids_.try_emplace(key);
  if (!inserted) return entry->second.grid;  // another thread built the same grid meanwhile
  lru_.push_front(key);
  entry->second = {grid, lru_.begin()};
  stats_.bytes += static_cast<int64_t>(grid.Bytes());
  while (stats_.bytes > options_.cache_bytes && !lru_.empty()) {
    auto victim = grids_.find(lru_.back());
    stats_.bytes -= static_cast<int64_t>(victim->second.grid.Bytes());
    grids_.erase(victim);
    lru_.pop_back();
  }
  return grid;
}

double NearestLookup::FallbackReach(const World& world) {
  return 32 * (world.radius_field() != nullptr ? world.max_spacing() : world.min_distance());
}

Status NearestLookup::CollectPoints(const World& world, const Rect& rect, PlanePoints& points) {
  if (engine_.ValidateQuery(world, rect).ok()) {
    StatusOr<PlanePoints> queried = engine_.Points(world, rect);
    if (!queried.ok()) return queried.status();
    points = std::move(*queried);
    return Status::Ok();
  }
  // Wider than the engine's area limit (a field world's square at a large r_max / r_min):
  // the same points, region by region.
  const RegionLayout layout(world);
  const RegionRange range = RegionsOverlapping(layout, rect);
  std::vector<RegionHandle> regions;
  for (int64_t j = range.low.j; j <= range.high.j; ++j) {
    for (int64_t i = range.low.i; i <= range.high.i; ++i) {
      StatusOr<RegionHandle> region = engine_.Region(world, {i, j});
      if (!region.ok()) return region.status();
      regions.push_back(std::move(*region));
    }
  }
  points = {};
  VisitPoints(regions, layout, rect, 0, SIZE_MAX, [&](Vec2 q, uint64_t id) {
    points.positions.push_back(q);
    points.ids.push_back(id);
  });
  return Status::Ok();
}

StatusOr<TwoNearest> NearestLookup::BruteForce(const World& world, Vec2 p) {
  const double d = world.min_distance();
  const double reach = FallbackReach(world);
  const double limit = RegionLayout(world).precision_limit();
  // Squares of half side reach / 8 to reach: on a maximal world the first one
  // always holds the answer (F2 < 2 d, or 2 r_max away from masks); the larger
  // ones guard against a world that is not, or a position near a mask. Every
  // point within (half side - slack) of p is in the square, despite rounding
  // of its corners (docs/noise.md).
  for (double half = reach / 8; half <= reach; half *= 2) {
    const Rect square = ClipToRange({p.x - half, p.y - half, p.x + half, p.y + half}, limit);
    PlanePoints points;
    if (Status status = CollectPoints(world, square, points); !status.ok()) return status;
    TwoNearest best;
    for (size_t k = 0; k < points.positions.size(); ++k) {
      const Vec2 q = points.positions[k];
      OfferCandidate(SquaredDistanceFrom(p, q), points.ids[k], q, best);
    }
    const double certified = half - 0x1.0p-12 * d;
    if (best.squared2 <= certified * certified) return best;
  }
  if (world.radius_field() != nullptr) {
    return OutOfRange("fewer than two points within 32 r_max = " + NumberText(reach) +
                      " of it (a masked area): Nearest answers positions within that of two "
                      "points");
  }
  return Status(StatusCode::kInternal,
                "world has fewer than two points within 32 * min_distance of (" +
                    std::to_string(p.x) + ", " + std::to_string(p.y) + "): it is not maximal");
}

NearestLookupStats NearestLookup::Stats() const {
  std::lock_guard lock(mutex_);
  NearestLookupStats stats = stats_;
  stats.grids_cached = static_cast<int64_t>(grids_.size());
  return stats;
}

}  // namespace scallop
