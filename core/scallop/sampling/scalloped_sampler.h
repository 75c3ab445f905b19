// A1 and A2: dart throwing with scalloped sectors (Dunbar &
// Humphreys 2006, section 3). Each point keeps its available neighbourhood,
// the part of the annulus d..r' around it that no disk covers; new points are
// drawn uniformly from a neighbourhood.
#pragma once

#include <vector>

#include "scallop/random/rng.h"
#include "scallop/sampling/sampling_problem.h"

namespace scallop {

enum class CandidateChoice {
  kByArea,   // A1: neighbourhood chosen with probability proportional to its area
  kUniform,  // A2: neighbourhood chosen uniformly
};

// How A1 places the bulk of its points; both follow the same law (tests/cell_darts_test.cc and
// tests/sampler_distribution_test.cc compare them).
enum class A1Bulk {
  // CellDarts (cell_darts.h) until only thin voids are left, then neighbourhoods: with
  // A1Reach::kAnywhere always, else on plain rectangles (no fixed or inert points, covered or
  // stop rectangles) at density 1.1 and up; elsewhere as below.
  kCells,
  // The paper's neighbourhoods throughout.
  kNeighbourhoods,
};

// Which available spots A1 draws its next point from (kByArea only).
enum class A1Reach {
  // Those within r' of a point: the paper's A1. Its sets grow from their frontier and are a
  // little denser than dart throwing's even at r' = 2 d (docs/quality.md); below 2 d, denser.
  kNearPoints,
  // All of them, near and far: dart throwing run to exhaustion, exactly. Cells for the bulk
  // (CellDarts with every cell open), neighbourhoods for the last voids, which by then all lie
  // within r' of a point. On a plane region's problem (a stop rectangle R, fixed and inert
  // points, covered rectangles; no torus): dart throwing in R with a rate that tapers past it,
  // until R is covered (CellDarts::Reach::kInStop; docs/design.md, "A1 world regions").
  // REQUIRES: density 2 and A1Bulk::kCells.
  kAnywhere,
};

// Samples until no neighbourhood is left (A1 with kAnywhere: until no spot is left).
// `bulk` and `reach` matter for kByArea only.
// REQUIRES: a problem that ValidateSamplerOptions accepted.
// Cost: A1 O(N log N) (a sum tree over areas; with cells, O(N) expected for the bulk), A2 O(N).
std::vector<Vec2> SampleScalloped(const SamplingProblem& problem, CandidateChoice choice, Rng& rng,
                                  A1Bulk bulk = A1Bulk::kCells,
                                  A1Reach reach = A1Reach::kNearPoints);

}  // namespace scallop
