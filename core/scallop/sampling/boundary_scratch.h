// BoundaryScratch: A3's working memory on a rectangle, kept by a caller that
// runs it again and again (a plane engine's thread, region after region), so
// that a run allocates little more than what it returns once the scratch has grown.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "scallop/geometry/vec2.h"
#include "scallop/sampling/available_boundary.h"
#include "scallop/sampling/boundary_exclusions.h"
#include "scallop/sampling/boundary_grid.h"
#include "scallop/sampling/candidate_boundary.h"

namespace scallop {

// A point of A3's candidate pool: its position, and its index in the run's points.
struct BoundaryCandidate {
  Vec2 position;
  int32_t index;
};

// What SampleBoundary keeps between runs. Each run starts from what a fresh
// scratch would give it, so what a scratch held before changes no output.
// Not thread-safe: one run at a time.
struct BoundaryScratch {
  std::optional<BoundaryGrid> grid;
  std::vector<Vec2> points;  // the run's, its inert and fixed points first
  std::vector<BoundaryCandidate> candidates;
  std::vector<Vec2> nearby;
  std::vector<KeyArc> outside_arcs;
  std::vector<uint32_t> pockets;
  AvailableBoundary boundary;
  std::optional<CandidateBoundary> candidate_boundary;
  BoundaryExclusions exclusions;
};

}  // namespace scallop
