// RegionScratch: the working memory of a region's run, kept by a caller that
// generates region after region (PlaneEngine lends one to each run from a
// ScratchPool), so that a run allocates little beyond the region it returns.
#pragma once

#include <vector>

#include "scallop/plane/neighbour_points.h"
#include "scallop/sampling/boundary_scratch.h"
#include "scallop/sampling/sampling_problem.h"

namespace scallop {

// What GenerateRegion keeps between runs. Each run starts from what a fresh
// scratch would give it, so what a scratch held before changes no point.
// Not thread-safe: one run at a time.
struct RegionScratch {
  NeighbourPoints gathered;
  BoundaryScratch boundary;              // A3's run
  std::vector<bool> placed_unprocessed;  // the run's flags (A3 and fields)
  // A later layer's region: room for its exclusion disks, listed by the engine
  // (RegionExclusions::DisksFor).
  std::vector<ExclusionDisk> exclusions;
};

}  // namespace scallop
