// GenerateRegion: gathers the constraining points, seeds the region's stream
// and runs the world's sampler on the region's rectangle.
#include "scallop/plane/region_generator.h"

#include <algorithm>
#include <cassert>

#include "scallop/plane/point_id.h"
#include "scallop/random/rng.h"
#include "scallop/sampling/boundary_sampler.h"
#include "scallop/sampling/scalloped_sampler.h"

namespace scallop {

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

RegionPoints GenerateRegion(const World& world, RegionKey key,
                            std::span<const RegionPoints* const> lower_neighbours) {
  const RegionLayout layout(world.min_distance);
  const Rect rect = layout.RegionRect(key);
  const double d = world.min_distance;
  // A point farther than this from the region neither constrains nor seeds
  // it; 1% more than needed is harmless (its neighbourhood in the region is
  // simply empty) and keeps the bound clear of rounding.
  const double reach = 1.01 * (UsesDensity(world.algorithm) ? world.density * d : d);

  std::vector<Vec2> fixed;
  for (const RegionPoints* neighbour : lower_neighbours) {
    for (const Vec2& p : neighbour->points) {
      const double dx = std::max({rect.x0 - p.x, 0.0, p.x - rect.x1});
      const double dy = std::max({rect.y0 - p.y, 0.0, p.y - rect.y1});
      if (dx * dx + dy * dy < reach * reach) fixed.push_back(p);
    }
  }

  const SamplingProblem problem{{rect, false}, d, world.density, fixed};
  Rng rng(HashWords({WorldFingerprint(world), static_cast<uint64_t>(key.i),
                     static_cast<uint64_t>(key.j)}));
  RegionPoints region{key, {}};
  switch (world.algorithm) {
    case Algorithm::kA1:
      region.points = SampleScalloped(problem, CandidateChoice::kByArea, rng);
      break;
    case Algorithm::kA2:
      region.points = SampleScalloped(problem, CandidateChoice::kUniform, rng);
      break;
    default:
      region.points = SampleBoundary(problem, rng);
      break;
  }
  // The hexagonal packing bound (296 points in a 16 d square) keeps k in its
  // 10 id bits; a violation would be a sampler bug, not bad input.
  assert(region.points.size() < (size_t{1} << kPointIdIndexBits));
  region.points.shrink_to_fit();
  return region;
}

}  // namespace scallop
