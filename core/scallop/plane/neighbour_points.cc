// GatherNeighbourPoints: a cheap first pass that bounds where a kept point
// can lie, then the exact tests for the few points inside that bound.
#include "scallop/plane/neighbour_points.h"

#include <algorithm>
#include <cstdint>

#include "scallop/geometry/rect_distance.h"
#include "scallop/plane/region_layout.h"

namespace scallop {
namespace {

// Where a region's run may place points: its rectangle and the parts of its
// higher-ranked neighbours inside the sampled rectangle (the lower-ranked
// neighbours' rectangles are covered already). Open cells side by side in a
// row of the 3 x 3 neighbourhood become one rectangle: they share the row's
// edges and meet exactly (RegionRect), so the distance to the joined
// rectangle is, bit for bit, the least distance to its parts. The gathering
// measures that for every point near the region: at most 3 rectangles
// instead of up to 7.
std::vector<Rect> OpenRects(const RegionLayout& layout, RegionKey key, const Rect& sampled) {
  std::vector<Rect> open;
  open.reserve(3);  // at most 3 (above): one allocation
  for (int64_t dj = -1; dj <= 1; ++dj) {
    bool extends_last = false;  // the cell to the left was open too
    for (int64_t di = -1; di <= 1; ++di) {
      const RegionKey n{key.i + di, key.j + dj};
      if ((di != 0 || dj != 0) && RegionRank(n) <= RegionRank(key)) {
        extends_last = false;
        continue;
      }
      const Rect r = layout.RegionRect(n);
      const Rect clipped{std::max(r.x0, sampled.x0), std::max(r.y0, sampled.y0),
                         std::min(r.x1, sampled.x1), std::min(r.y1, sampled.y1)};
      if (extends_last) {
        open.back().x1 = clipped.x1;
      } else {
        open.push_back(clipped);
      }
      extends_last = true;
    }
  }
  return open;
}

double SquaredDistanceToAny(const std::vector<Rect>& rects, Vec2 p) {
  double nearest = SquaredDistanceInLanes(rects.front(), p);
  for (const Rect& r : rects) nearest = std::min(nearest, SquaredDistanceInLanes(r, p));
  return nearest;
}

Rect Bounds(const Rect& a, const Rect& b) {
  return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

Rect Intersection(const Rect& a, const Rect& b) {
  return {std::max(a.x0, b.x0), std::max(a.y0, b.y0), std::min(a.x1, b.x1), std::min(a.y1, b.y1)};
}

// A rectangle that holds every point the exact tests can keep: within
// `reach` of the sampled rectangle and `inert_reach` of an open one. The
// 0.01 d to spare is far above the rounding of these sums and differences
// (coordinates stay under 2^32 d, so their last bit is under 2^-20 d).
Rect KeepableZone(const Rect& sampled, const std::vector<Rect>& open, double reach,
                  double inert_reach, double d) {
  Rect bounds_of_open = open.front();
  for (const Rect& r : open) bounds_of_open = Bounds(bounds_of_open, r);
  return Intersection(Grown(sampled, reach + 0.01 * d),
                      Grown(bounds_of_open, inert_reach + 0.01 * d));
}

// Writes the indices (over `own` then `spill`) of the points strictly inside
// `zone` to near[0, n) in order and returns n. Branch-free: whether a point
// is near follows no pattern a branch predictor could learn, and most are not.
size_t IndicesInZone(std::span<const Vec2> own, std::span<const Vec2> spill, const Rect& zone,
                     std::vector<uint32_t>& near) {
  // Both coordinates at once, in the two lanes of an SSE2 register.
  using Doubles = double __attribute__((vector_size(16)));
  using Bits = int64_t __attribute__((vector_size(16)));
  const Doubles low = {zone.x0, zone.y0}, high = {zone.x1, zone.y1};
  near.resize(own.size() + spill.size());
  size_t count = 0;
  uint32_t k = 0;
  for (const std::span<const Vec2> points : {own, spill}) {
    for (const Vec2& p : points) {
      const Doubles v = {p.x, p.y};
      const Bits inside = (v > low) & (v < high);
      near[count] = k++;
      count += static_cast<size_t>(inside[0] & inside[1]) & 1;
    }
  }
  return count;
}

}  // namespace

NeighbourPoints GatherNeighbourPoints(const World& world, RegionKey key,
                                      std::span<const RegionPoints* const> lower_neighbours) {
  NeighbourPoints gathered;
  GatherNeighbourPoints(world, key, lower_neighbours, gathered);
  return gathered;
}

void GatherNeighbourPoints(const World& world, RegionKey key,
                           std::span<const RegionPoints* const> lower_neighbours,
                           NeighbourPoints& gathered) {
  const RegionLayout layout(world);
  // d, or r_max for a field world: the farthest two points can conflict.
  const double d = world.max_spacing();
  const Rect rect = layout.RegionRect(key);
  const Rect sampled = Grown(rect, SamplingMargin(world));
  // A point farther than this from the sampled rectangle neither constrains
  // nor seeds it; 1% more than needed is harmless (its neighbourhood there is
  // simply empty) and keeps the bound clear of rounding.
  const double reach = SeedReach(world);
  // A seed's neighbourhood reaches `reach` further, and where it enters a
  // covered rectangle the points covering that are within d.
  const double inert_reach = 2 * reach + 1.01 * d;
  const std::vector<Rect> open = OpenRects(layout, key, sampled);
  const Rect zone = KeepableZone(sampled, open, reach, inert_reach, d);

  gathered.fixed.clear();
  gathered.inert.clear();
  gathered.adopted.clear();
  gathered.covered.clear();
  std::vector<uint32_t>& near = gathered.near;
  // Filed without a branch on each point (whether a point is fixed, inert or left out follows
  // no pattern a predictor could learn): each list is sized for every point in the zone, each
  // point written to all three, and each count moved past it only where it belongs. The lists
  // keep the order of the branching version, so the same bits.
  size_t fixed_count = 0, inert_count = 0, adopted_count = 0;
  const double reach_squared = reach * reach, inert_squared = inert_reach * inert_reach;
  // Room for every neighbour point at once: sized a neighbour at a time, the lists were copied
  // as they grew.
  size_t most = 0;
  for (const RegionPoints* neighbour : lower_neighbours) {
    most += neighbour->points.size() - neighbour->adopted + neighbour->spill.size();
  }
  gathered.fixed.reserve(most);
  gathered.inert.reserve(most);
  gathered.adopted.reserve(most);
  gathered.covered.reserve(lower_neighbours.size());
  for (const RegionPoints* neighbour : lower_neighbours) {
    gathered.covered.push_back(layout.RegionRect(neighbour->key));
    // A neighbour's adopted points are another lower-ranked neighbour's
    // spill, or lie too far from the sampled rectangle to matter.
    const std::span<const Vec2> own(neighbour->points.begin() + neighbour->adopted,
                                    neighbour->points.end());
    const std::span<const Vec2> spill(neighbour->spill);
    const size_t count = IndicesInZone(own, spill, zone, near);
    gathered.fixed.resize(fixed_count + count);
    gathered.inert.resize(inert_count + count);
    gathered.adopted.resize(adopted_count + count);
    const std::vector<bool>& unprocessed = neighbour->unprocessed;
    const bool all_may_seed = unprocessed.empty();
    for (size_t n = 0; n < count; ++n) {
      const uint32_t index = near[n];  // also the index into `unprocessed`
      const bool in_spill = index >= own.size();
      const Vec2 p = in_spill ? spill[index - own.size()] : own[index];
      // The zone holds the rectangle, so every point to adopt is seen here.
      gathered.adopted[adopted_count] = p;
      adopted_count += in_spill & ContainsBranchFree(rect, p);
      const bool near_sampled = SquaredDistanceInLanes(sampled, p) < reach_squared;
      const bool may_seed = all_may_seed || unprocessed[index];
      const double squared_distance = SquaredDistanceToAny(open, p);
      const bool fixed = near_sampled & may_seed & (squared_distance < reach_squared);
      gathered.fixed[fixed_count] = p;
      fixed_count += fixed;
      gathered.inert[inert_count] = p;
      inert_count += near_sampled & !fixed & (squared_distance < inert_squared);
    }
  }
  gathered.fixed.resize(fixed_count);
  gathered.inert.resize(inert_count);
  gathered.adopted.resize(adopted_count);
}

}  // namespace scallop
