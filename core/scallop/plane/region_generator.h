// Generation of one region of a world: a pure function of (world, region key,
// the points of its lower-ranked neighbours). See docs/design.md, "Regions".
#pragma once

#include <array>
#include <memory>
#include <span>
#include <vector>

#include "scallop/geometry/vec2.h"
#include "scallop/plane/region_layout.h"
#include "scallop/plane/world.h"
#include "scallop/sampling/sampling_problem.h"

namespace scallop {

// A region's sampler runs on its rectangle grown by this margin and stops
// once the rectangle is covered; the points it placed beyond the rectangle
// (its spill, a natural growth front) are owned by the higher-ranked
// neighbours they fall in, which adopt them and continue the growth. With
// S = 16 d, 6.5 d keeps all of a region's points within its 8 neighbours and
// two regions' spill at least 3 d apart unless they are neighbours.
// See docs/design.md, "Growing regions".
inline constexpr double kSamplingMarginInD = 6.5;

// The same margin for a radius-field world, in units of r_max (regions are
// kFieldRegionSideInRMax = 6 r_max wide). A run processes only candidates
// whose curve may reach its region, so its spill stays within about 2 r_max
// of it where R is near r_max (2 R / (1 - L) at the very worst), and the wall
// at 2.25 r_max is seldom met; with 1.25 or 0.75 r_max the wall froze a
// straight front, 20% too dense before it and 30% too sparse after it. Two
// points conflict only when less than max(R(p), R(q)) <= r_max apart, and the
// spill of two regions that are not neighbours stays S - 2 m = 1.5 r_max
// apart. docs/design.md, "Field worlds on the plane".
inline constexpr double kFieldSamplingMarginInRMax = 2.25;

// The margin a region of `world` is sampled with: 6.5 d, or 2.25 r_max.
double SamplingMargin(const World& world);

// How far from the rectangles open to a run a lower-ranked neighbour's point
// may seed it (and constrain it, for A3 and fields): A3 d, A1 and A2 r' (the
// density times d), a field r_max / (1 - L), the farthest a point's curve
// reaches; each plus 1%.
double SeedReach(const World& world);

// One generated region: the world's points in its rectangle, and the points
// it placed in higher-ranked neighbours, which those adopt.
struct RegionPoints {
  RegionKey key;
  // First the lower-ranked neighbours' spill that lies in the rectangle
  // (neighbours in LowerRankedNeighbours order, each in its spill order),
  // then the region's own points in generation order. The k-th point's id
  // is EncodePointId(key, k).
  std::vector<Vec2> points;
  // How many of `points` are adopted spill.
  uint32_t adopted = 0;
  // The region's own points outside its rectangle, in generation order.
  std::vector<Vec2> spill;
  // A3 only (empty otherwise): for the own points, then the spill, whether
  // the run left them unprocessed. Only those can seed a later region.
  std::vector<bool> unprocessed;

  // Bytes this region holds in memory, for the cache's budget.
  size_t Bytes() const {
    return sizeof(RegionPoints) + (points.capacity() + spill.capacity()) * sizeof(Vec2) +
           unprocessed.capacity() / 8;
  }
};

struct RegionScratch;

// Up to 8 region keys, held in place: the engine asks for a region's
// neighbours several times a region, and a vector's allocation each time
// showed in its profile.
class NeighbourKeys {
 public:
  void push_back(RegionKey key) { keys_[count_++] = key; }  // REQUIRES: size() < 8
  const RegionKey* begin() const { return keys_.data(); }
  const RegionKey* end() const { return keys_.data() + count_; }
  size_t size() const { return count_; }
  bool empty() const { return count_ == 0; }
  const RegionKey& operator[](size_t n) const { return keys_[n]; }

 private:
  std::array<RegionKey, 8> keys_{};
  size_t count_ = 0;
};

// The lower-ranked 8-neighbours of `key` (all 8 for a rank-3 region, none for
// rank 0), in the canonical order the generator expects them: rows bottom to
// top, left to right within a row.
NeighbourKeys LowerRankedNeighbours(RegionKey key);

// Generates region `key`. `lower_neighbours[n]` must be the generated region
// LowerRankedNeighbours(key)[n]. The sampler runs on the rectangle grown by
// SamplingMargin(world) until the rectangle is covered; the neighbours' points
// (and spill) within reach of it (SeedReach) constrain the
// new ones and seed their neighbourhoods, and no new point lands in a
// neighbour's rectangle. The region's random stream is
// Rng(HashWords({world.fingerprint(), i, j})). A field world's regions are
// grown by SampleFieldProblem (sampling/field_sampler.h).
// Cost: O(points placed), about 220 for
// A3 on average (a rank-0 region places more, a rank-3 region fewer); a
// field world's region holds up to 0.86 (6 r_max / R)^2 points where the
// field is near R.
// The world of a layer generated after others (World::earlier_layers()) also
// keeps clear of `exclusions`: every point of the earlier layers strictly
// within D of the sampled rectangle, with D as its radius (RegionExclusions).
// A3 (a constant layer) cuts them from its circles and processes their own
// circles too; the field sampler (a field layer) treats them as masked.
// With `scratch` (region_scratch.h), the run works in its memory and leaves
// it there for the caller's next run; the region is the same with it or without.
RegionPoints GenerateRegion(const World& world, RegionKey key,
                            std::span<const RegionPoints* const> lower_neighbours,
                            std::span<const ExclusionDisk> exclusions = {},
                            RegionScratch* scratch = nullptr);

// The rectangle a region of `world` samples: its own grown by SamplingMargin.
Rect SampledRect(const World& world, RegionKey key);

}  // namespace scallop
