// Generation of one region of a world: a pure function of (world, region key,
// the points of its lower-ranked neighbours). See docs/design.md, "Regions".
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "scallop/geometry/vec2.h"
#include "scallop/plane/region_layout.h"
#include "scallop/plane/world.h"

namespace scallop {

// One generated region: its points in generation order. The k-th point's id
// is EncodePointId(key, k).
struct RegionPoints {
  RegionKey key;
  std::vector<Vec2> points;

  // Bytes this region holds in memory, for the cache's budget.
  size_t Bytes() const { return sizeof(RegionPoints) + points.capacity() * sizeof(Vec2); }
};

// The lower-ranked 8-neighbours of `key`, in the canonical order the
// generator expects them: rows bottom to top, left to right within a row.
std::vector<RegionKey> LowerRankedNeighbours(RegionKey key);

// Generates region `key`. `lower_neighbours[n]` must be the generated region
// LowerRankedNeighbours(key)[n]. Its points within reach of the region (d for
// A3, r' for A1 and A2) constrain the new ones and seed their neighbourhoods;
// the region's random stream is Rng(HashWords({WorldFingerprint(world), i, j})).
// REQUIRES: ValidateWorld(world).ok(). Cost: O(points), about 220 points for A3.
RegionPoints GenerateRegion(const World& world, RegionKey key,
                            std::span<const RegionPoints* const> lower_neighbours);

}  // namespace scallop
