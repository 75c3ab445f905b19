// GenerateRegion: gathers the neighbours' points (seeding, inert, adopted),
// grows the region from them until it is covered, and sorts what it placed.
#include "scallop/plane/region_generator.h"

#include <algorithm>
#include <cassert>

#include "scallop/plane/point_id.h"
#include "scallop/random/rng.h"
#include "scallop/sampling/boundary_sampler.h"
#include "scallop/sampling/scalloped_sampler.h"

namespace scallop {

// A region's points stay within its 8 neighbours, and the points of two
// regions that are not neighbours (which never see each other) stay more
// than d apart: S - 2 m >= 2 d.
static_assert(kSamplingMarginInD < kRegionSideInD &&
              kRegionSideInD - 2 * kSamplingMarginInD >= 2.0);

std::vector<RegionKey> LowerRankedNeighbours(RegionKey key) {
  std::vector<RegionKey> neighbours;
  const int rank = RegionRank(key);
  for (int64_t dj = -1; dj <= 1; ++dj) {
    for (int64_t di = -1; di <= 1; ++di) {
      const RegionKey n{key.i + di, key.j + dj};
      if ((di != 0 || dj != 0) && RegionRank(n) < rank) neighbours.push_back(n);
    }
  }
  return neighbours;
}

namespace {

// Where a region's run may place points: its rectangle and the parts of its
// higher-ranked neighbours inside the sampled rectangle. The lower-ranked
// neighbours' rectangles are covered already.
std::vector<Rect> OpenRects(const RegionLayout& layout, RegionKey key, const Rect& sampled) {
  std::vector<Rect> open{layout.RegionRect(key)};
  for (int64_t dj = -1; dj <= 1; ++dj) {
    for (int64_t di = -1; di <= 1; ++di) {
      const RegionKey n{key.i + di, key.j + dj};
      if (RegionRank(n) <= RegionRank(key)) continue;
      const Rect r = layout.RegionRect(n);
      open.push_back({std::max(r.x0, sampled.x0), std::max(r.y0, sampled.y0),
                      std::min(r.x1, sampled.x1), std::min(r.y1, sampled.y1)});
    }
  }
  return open;
}

double SquaredDistanceToAny(const std::vector<Rect>& rects, Vec2 p) {
  double nearest = SquaredDistance(rects.front(), p);
  for (const Rect& r : rects) nearest = std::min(nearest, SquaredDistance(r, p));
  return nearest;
}

}  // namespace

RegionPoints GenerateRegion(const World& world, RegionKey key,
                            std::span<const RegionPoints* const> lower_neighbours) {
  const RegionLayout layout(world.min_distance);
  const double d = world.min_distance;
  const Rect rect = layout.RegionRect(key);
  const Rect sampled = Grown(rect, kSamplingMarginInD * d);
  // A point farther than this from the sampled rectangle neither constrains
  // nor seeds it; 1% more than needed is harmless (its neighbourhood there is
  // simply empty) and keeps the bound clear of rounding.
  const double reach = 1.01 * (UsesDensity(world.algorithm) ? world.density * d : d);

  // The neighbours' points constrain and seed the run; their spill inside the
  // rectangle is adopted; their rectangles, covered already, stay closed.
  // Only points within `reach` of the open rectangles can seed anything (and
  // for A3 only those their own run left unprocessed). Points up to
  // 2 reach + d from them are needed too, as inert points: a seed's
  // neighbourhood reaches `reach` further, and where it enters a covered
  // rectangle the points covering that are within d.
  const std::vector<Rect> open = OpenRects(layout, key, sampled);
  const double inert_reach = 2 * reach + 1.01 * d;

  RegionPoints region{key, {}, 0, {}, {}};
  std::vector<Vec2> fixed, inert;
  std::vector<Rect> covered;
  for (const RegionPoints* neighbour : lower_neighbours) {
    covered.push_back(layout.RegionRect(neighbour->key));
    // Each point once, from the region that placed it: a neighbour's adopted
    // points are the spill of another lower-ranked neighbour (or lie too far
    // from the sampled rectangle to matter).
    const std::span<const Vec2> own(neighbour->points.begin() + neighbour->adopted,
                                    neighbour->points.end());
    size_t k = 0;  // over own, then spill: the index into `unprocessed`
    for (const std::span<const Vec2> points : {own, std::span<const Vec2>(neighbour->spill)}) {
      for (const Vec2& p : points) {
        const bool may_seed = neighbour->unprocessed.empty() || neighbour->unprocessed[k];
        ++k;
        if (SquaredDistance(sampled, p) >= reach * reach) continue;
        const double squared_distance = SquaredDistanceToAny(open, p);
        if (may_seed && squared_distance < reach * reach) {
          fixed.push_back(p);
        } else if (squared_distance < inert_reach * inert_reach) {
          inert.push_back(p);
        }
      }
    }
    for (const Vec2& p : neighbour->spill) {
      if (rect.Contains(p)) region.points.push_back(p);
    }
  }

  region.adopted = static_cast<uint32_t>(region.points.size());
  // Run until the rectangle is covered, no further: the points beyond it are
  // a natural growth front for the higher-ranked neighbours to continue. A
  // rank-0 region grows from a point near its centre, so its front reaches
  // every seam (docs/design.md, "Growing regions").
  const Vec2 centre{(rect.x0 + rect.x1) / 2, (rect.y0 + rect.y1) / 2};
  SamplingProblem problem;
  problem.domain = {sampled, false};
  problem.min_distance = d;
  problem.density = world.density;
  problem.fixed_points = fixed;
  problem.inert_points = inert;
  problem.covered_rects = covered;
  problem.stop_when_covered = rect;
  problem.seed_area = Grown(Rect{centre.x, centre.y, centre.x, centre.y}, d / 2);
  Rng rng(HashWords({WorldFingerprint(world), static_cast<uint64_t>(key.i),
                     static_cast<uint64_t>(key.j)}));
  std::vector<Vec2> placed;
  std::vector<bool> placed_unprocessed;
  switch (world.algorithm) {
    case Algorithm::kA1:
      placed = SampleScalloped(problem, CandidateChoice::kByArea, rng);
      break;
    case Algorithm::kA2:
      placed = SampleScalloped(problem, CandidateChoice::kUniform, rng);
      break;
    default:
      placed = SampleBoundary(problem, rng, &placed_unprocessed);
      break;
  }
  // Every placed point is a world point: outside the rectangle it lies in a
  // higher-ranked neighbour (the covered rectangles are closed to it), which
  // adopts it. A point whose circle crossed the sampled rectangle's edge had
  // that part clipped, not covered: it may still seed a later region.
  const Rect clipped_near = Grown(sampled, -1.01 * d);
  std::vector<bool> spill_unprocessed;
  for (size_t k = 0; k < placed.size(); ++k) {
    const bool inside = rect.Contains(placed[k]);
    (inside ? region.points : region.spill).push_back(placed[k]);
    if (!placed_unprocessed.empty()) {
      const bool may_seed = placed_unprocessed[k] || !clipped_near.Contains(placed[k]);
      (inside ? region.unprocessed : spill_unprocessed).push_back(may_seed);
    }
  }
  region.unprocessed.insert(region.unprocessed.end(), spill_unprocessed.begin(),
                            spill_unprocessed.end());
  // The hexagonal packing bound (296 points in a 16 d square) keeps k in its
  // 10 id bits; a violation would be a sampler bug, not bad input.
  assert(region.points.size() < (size_t{1} << kPointIdIndexBits));
  region.points.shrink_to_fit();
  region.spill.shrink_to_fit();
  return region;
}

}  // namespace scallop
