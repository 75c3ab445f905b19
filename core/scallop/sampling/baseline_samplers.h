// Baseline samplers, for comparison with A1-A3 in tests and benchmarks only:
// plain and exhaustive dart throwing, Mitchell's best candidate, Bridson.
#pragma once

#include <cstdint>
#include <vector>

#include "scallop/random/rng.h"
#include "scallop/sampling/sampling_problem.h"

namespace scallop {

// Dart throwing: uniform darts, each kept when at least d from every kept
// point; stops after `failure_limit` rejected darts in a row. Not maximal.
// O(N * failure_limit) in the worst case.
std::vector<Vec2> SampleDartThrowing(const SamplingProblem& problem, int64_t failure_limit,
                                     Rng& rng);

// Dart throwing run to exhaustion, so the set is maximal and distributed as
// dart throwing (random sequential adsorption at its jamming limit). Darts go
// to uniformly chosen cells of a quadtree of not-yet-covered cells (Ebeida et
// al. 2011): a cell is dropped once one disk covers it, and all cells split in
// four when darts at the current level keep missing. Uniform over the
// uncovered area at every step, so the distribution is dart throwing's.
std::vector<Vec2> SampleExhaustiveDartThrowing(const SamplingProblem& problem, Rng& rng);

// Mitchell's best candidate: the i-th point is the best of factor * i uniform
// candidates (farthest from the set); stops when the best is closer than d.
// O(N^2 * factor) in the worst case: the paper's slow baseline.
std::vector<Vec2> SampleBestCandidate(const SamplingProblem& problem, int factor, Rng& rng);

// Bridson 2007: from a random active point try `attempts` uniform points of
// the annulus d..2d; keep the first valid one or retire the active point.
std::vector<Vec2> SampleBridson(const SamplingProblem& problem, int attempts, Rng& rng);

}  // namespace scallop
