// GenerateRegion: takes the neighbours' points (neighbour_points.h), grows the
// region from them until it is covered, and sorts what it placed.
#include "scallop/plane/region_generator.h"

#include <algorithm>
#include <cassert>

#include "scallop/plane/neighbour_points.h"
#include "scallop/plane/point_id.h"
#include "scallop/plane/region_scratch.h"
#include "scallop/random/rng.h"
#include "scallop/sampling/boundary_sampler.h"
#include "scallop/sampling/field_sampler.h"
#include "scallop/sampling/scalloped_sampler.h"

namespace scallop {

// A region's points stay within its 8 neighbours, and the points of two
// regions that are not neighbours (which never see each other) stay more
// than d apart: S - 2 m >= 2 d.
static_assert(kSamplingMarginInD < kRegionSideInD &&
              kRegionSideInD - 2 * kSamplingMarginInD >= 2.0);
// The same for a field world, in r_max, with the reach of a field point's
// curve (at most 2 r_max at the slope bound 1/2, plus 1%): every point a run
// gathers lies within its 8 neighbours, and no two points of regions that are
// not neighbours can conflict (they are more than r_max apart).
static_assert(kFieldSamplingMarginInRMax + 2.02 < kFieldRegionSideInRMax &&
              kFieldRegionSideInRMax - 2 * kFieldSamplingMarginInRMax > 1.25);

double SamplingMargin(const World& world) {
  return world.radius_field() != nullptr ? kFieldSamplingMarginInRMax * world.max_spacing()
                                         : kSamplingMarginInD * world.min_distance();
}

double SeedReach(const World& world) {
  if (const RadiusField* field = world.radius_field()) {
    return 1.01 * field->r_max() / (1.0 - field->Slope());
  }
  const double d = world.min_distance();
  return 1.01 * (UsesDensity(world.algorithm()) ? world.density() * d : d);
}

NeighbourKeys LowerRankedNeighbours(RegionKey key) {
  NeighbourKeys neighbours;
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

// Stores the adopted points, then the run's points: those in the rectangle
// as the region's own, the others as its spill, each in run order, with A3's
// flags (own, then spill) when the run gave them. Exact capacities, as the
// cache counts them.
void StorePlaced(const std::vector<Vec2>& adopted_points, const std::vector<Vec2>& placed,
                 const std::vector<bool>& placed_unprocessed, const Rect& rect,
                 const Rect& clipped_near, RegionPoints& region) {
  const size_t adopted = adopted_points.size();
  size_t inside = 0;
  for (const Vec2& p : placed) inside += ContainsBranchFree(rect, p);
  region.points.reserve(adopted + inside);
  region.points.assign(adopted_points.begin(), adopted_points.end());
  region.points.resize(adopted + inside);
  region.adopted = static_cast<uint32_t>(adopted);
  region.spill.resize(placed.size() - inside);
  const bool has_flags = !placed_unprocessed.empty();
  if (has_flags) region.unprocessed.assign(placed.size(), false);
  size_t own = 0, spill = 0;
  for (size_t k = 0; k < placed.size(); ++k) {
    const bool in_rect = ContainsBranchFree(rect, placed[k]);
    *(in_rect ? region.points.data() + adopted + own : region.spill.data() + spill) = placed[k];
    if (has_flags) {
      // A point whose circle crossed the sampled rectangle's edge had that
      // part clipped, not covered: it may still seed a later region.
      region.unprocessed[in_rect ? own : inside + spill] =
          placed_unprocessed[k] || !ContainsBranchFree(clipped_near, placed[k]);
    }
    own += in_rect;
    spill += !in_rect;
  }
}

// The run of a constant world's region, by its algorithm.
std::vector<Vec2> SampleConstant(const World& world, const SamplingProblem& problem, Rng& rng,
                                 std::vector<bool>* unprocessed, BoundaryScratch& scratch) {
  switch (world.algorithm()) {
    case WorldAlgorithm::kA1:
      // Exact dart throwing in the region at density 2 (CellDarts::Reach::kInStop); the
      // paper's A1 below, where its restriction to r' is the point.
      return SampleScalloped(problem, CandidateChoice::kByArea, rng, A1Bulk::kCells,
                             world.density() == 2.0 ? A1Reach::kAnywhere : A1Reach::kNearPoints);
    case WorldAlgorithm::kA2:
      return SampleScalloped(problem, CandidateChoice::kUniform, rng);
    case WorldAlgorithm::kA3:
      break;
  }
  return SampleBoundary(problem, rng, unprocessed, &scratch);
}

}  // namespace

Rect SampledRect(const World& world, RegionKey key) {
  return Grown(RegionLayout(world).RegionRect(key), SamplingMargin(world));
}

RegionPoints GenerateRegion(const World& world, RegionKey key,
                            std::span<const RegionPoints* const> lower_neighbours,
                            std::span<const ExclusionDisk> exclusions, RegionScratch* scratch) {
  RegionScratch own_scratch;
  RegionScratch& work = scratch != nullptr ? *scratch : own_scratch;
  const RegionLayout layout(world);
  const double d = world.min_distance();
  const Rect rect = layout.RegionRect(key);
  const Rect sampled = Grown(rect, SamplingMargin(world));
  // The neighbours' points constrain and seed the run; their spill inside the
  // rectangle is adopted; their rectangles, covered already, stay closed.
  NeighbourPoints& gathered = work.gathered;
  GatherNeighbourPoints(world, key, lower_neighbours, gathered);

  // Run until the rectangle is covered, no further: the points beyond it are
  // a natural growth front for the higher-ranked neighbours to continue. A
  // rank-0 region grows from a point near its centre, so its front reaches
  // every seam (docs/design.md, "Growing regions").
  const Vec2 centre{(rect.x0 + rect.x1) / 2, (rect.y0 + rect.y1) / 2};
  SamplingProblem problem;
  problem.domain = {sampled, false};
  problem.min_distance = d;
  problem.density = world.density();
  problem.fixed_points = gathered.fixed;
  problem.inert_points = gathered.inert;
  problem.covered_rects = gathered.covered;
  problem.stop_when_covered = rect;
  problem.seed_area =
      Grown(Rect{centre.x, centre.y, centre.x, centre.y}, world.SpacingAt(centre) / 2);
  problem.exclusions = exclusions;
  Rng rng(
      HashWords({world.fingerprint(), static_cast<uint64_t>(key.i), static_cast<uint64_t>(key.j)}));
  std::vector<Vec2> placed;
  std::vector<bool>& placed_unprocessed = work.placed_unprocessed;
  placed_unprocessed.clear();  // A1 and A2 give no flags
  // A point whose curve (circle) crossed the sampled rectangle's edge had that
  // part clipped, not covered: it may still seed a later region.
  double clipped_reach = 1.01 * d;
  if (const RadiusField* field = world.radius_field()) {
    placed = SampleFieldProblem(problem, *field, rng, &placed_unprocessed);
    clipped_reach = SeedReach(world);
  } else {
    placed = SampleConstant(world, problem, rng, &placed_unprocessed, work.boundary);
  }
  // Every placed point is a world point: outside the rectangle it lies in a
  // higher-ranked neighbour (the covered rectangles are closed to it), which
  // adopts it.
  RegionPoints region{key, {}, 0, {}, {}};
  StorePlaced(gathered.adopted, placed, placed_unprocessed, rect, Grown(sampled, -clipped_reach),
              region);
  // The packing bound (296 points in a 16 d square; region_layout.h for
  // fields) keeps k in its id bits; a violation would be a sampler bug, not
  // bad input.
  assert(region.points.size() < (size_t{1} << layout.point_id_index_bits()));
  return region;
}

}  // namespace scallop
