// What a region's run takes from its lower-ranked neighbours: the points that
// seed and constrain it, the spill it adopts and the rectangles that are
// closed to it. See docs/design.md, "Growing regions".
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "scallop/geometry/rect.h"
#include "scallop/geometry/vec2.h"
#include "scallop/plane/region_generator.h"
#include "scallop/plane/world.h"

namespace scallop {

// Rect::Contains without its branches, for the loops over a region's points that gather and
// store them: whether a point lies in the rectangle follows no pattern a branch predictor
// could learn.
inline bool ContainsBranchFree(const Rect& r, Vec2 p) {
  return (r.x0 <= p.x) & (p.x < r.x1) & (r.y0 <= p.y) & (p.y < r.y1);
}

struct NeighbourPoints {
  std::vector<Vec2> fixed;     // constrain and seed: SamplingProblem::fixed_points
  std::vector<Vec2> inert;     // only constrain: SamplingProblem::inert_points
  std::vector<Vec2> adopted;   // the neighbours' spill in the region's rectangle
  std::vector<Rect> covered;   // the neighbours' rectangles: SamplingProblem::covered_rects
  std::vector<uint32_t> near;  // the gathering's own working list, kept for reuse
};

// Gathers, for region `key` (sampled on its rectangle grown by
// kSamplingMarginInD d), the own points and spill of its lower-ranked
// neighbours (`lower_neighbours[n]` is LowerRankedNeighbours(key)[n]), each
// point once, from the region that placed it. A point within `reach` of the
// sampled rectangle (d for A3, r' for A1 and A2, plus 1%) is
//   - fixed if it is within `reach` of the rectangles open to the run (the
//     region's and its higher-ranked neighbours') and may seed (for A3: its
//     own run left it unprocessed);
//   - else inert if it is within 2 reach + 1.01 d of them;
//   - else left out.
// Each list holds the neighbours in order, each one's own points then its
// spill, in their stored order: the sampler's output depends on it.
// Cost: a few comparisons for each of
// the neighbours' points (about 3,000 for a rank-3 region), and an exact
// measure only for the few hundred near the region.
NeighbourPoints GatherNeighbourPoints(const World& world, RegionKey key,
                                      std::span<const RegionPoints* const> lower_neighbours);
// The same into `gathered`, whose lists are cleared first and keep their
// memory: for a caller that gathers region after region (RegionScratch).
void GatherNeighbourPoints(const World& world, RegionKey key,
                           std::span<const RegionPoints* const> lower_neighbours,
                           NeighbourPoints& gathered);

}  // namespace scallop
