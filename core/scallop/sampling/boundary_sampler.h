// A3, boundary sampling (Dunbar & Humphreys 2006, section 4): new points go
// only on the circle of radius d around an earlier point, on the part of it
// (its available boundary) that no other point's disk covers. O(N).
#pragma once

#include <vector>

#include "scallop/random/rng.h"
#include "scallop/sampling/sampling_problem.h"

namespace scallop {

struct BoundaryScratch;

// Samples the domain until every point's available boundary is empty; the
// result is maximal for SpacingFor(d, ...) and every pair is at least d apart
// in double precision. Points come back in generation order (fixed points
// excluded). REQUIRES: a problem that ValidateSamplerOptions accepted.
// Cost: O(N) time, about 40 bytes of grid per point (60 on a torus).
// With `unprocessed`, also says which returned points the run never picked
// (unprocessed[k] for point k): only those can have any boundary left when a
// stop rectangle ended the run early, so a later run that takes the points as
// fixed may pass the others as inert.
// With `scratch` (boundary_scratch.h), works in its memory and leaves it
// there for the caller's next run; the points are the same with it or without.
std::vector<Vec2> SampleBoundary(const SamplingProblem& problem, Rng& rng,
                                 std::vector<bool>* unprocessed = nullptr,
                                 BoundaryScratch* scratch = nullptr);

}  // namespace scallop
