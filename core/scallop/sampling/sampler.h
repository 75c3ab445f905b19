// The one entry point to every bounded-domain sampler: validate the options,
// then run the chosen algorithm. Points come back in generation order.
//
// Algorithms (Dunbar & Humphreys 2006, see docs/design.md):
//   kA1  dart throwing run to exhaustion, exactly, at density 2 (cells, then scalloped
//        sectors for the last voids); below 2, the paper's A1, restricted to spots within r'
//        of the set, O(N log N)
//   kA2  A1 with the candidate chosen uniformly, O(N)
//   kA3  boundary sampling, O(N)
// Baselines, for comparison only:
//   kDartThrowing   plain dart throwing until `dart_failure_limit` misses in a row
//   kBestCandidate  Mitchell's best candidate, stopped when the best of its
//                   candidates is closer than d to the set
//   kBridson        Bridson 2007 with `bridson_attempts` tries per active point
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "scallop/base/precision_range.h"
#include "scallop/base/status.h"
#include "scallop/geometry/domain.h"
#include "scallop/geometry/rect.h"
#include "scallop/geometry/vec2.h"

namespace scallop {

enum class Algorithm { kA1, kA2, kA3, kDartThrowing, kBestCandidate, kBridson };

// "a1", "a2", "a3", "dart", "best-candidate", "bridson".
std::string_view AlgorithmName(Algorithm algorithm);
StatusOr<Algorithm> ParseAlgorithm(std::string_view name);
// True for the algorithms whose density the outer radius r' tunes (A1, A2).
bool UsesDensity(Algorithm algorithm);

struct SamplerOptions {
  Algorithm algorithm = Algorithm::kA3;
  Domain domain;
  // Minimum distance d between any two points (the paper's 2r).
  double min_distance = 1.0;
  // r' / 2r in (1, 2]: the outer radius of A1 and A2 neighbourhoods over d.
  // For A1, 2 is exact dart throwing (new points anywhere still available); smaller restricts
  // new points to within r' of the set, which gives denser sets. Ignored by others.
  double density = 2.0;
  uint64_t seed = 0;
  // Dart throwing stops after this many rejected darts in a row...
  int64_t dart_failure_limit = 100000;
  // ...or, when exhaustive, only once no spot is left (a maximal set).
  bool dart_exhaustive = false;
  // Bridson's k: candidates tried around an active point before retiring it.
  int bridson_attempts = 30;
  // Mitchell's best candidate draws this many candidates per point already placed.
  int best_candidate_factor = 10;
};

// Largest point count a bounded sampler will produce (about 2 GiB of working
// memory for A1); domains whose area would exceed it are rejected.
inline constexpr double kMaxSamplerPoints = 64e6;

// Checks every field and returns a status naming the first bad one:
// INVALID_ARGUMENT for non-finite or inverted rectangles, d outside
// [kSmallestMinDistance, kLargestMinDistance], density outside (1, 2] (A1, A2), a torus side
// shorter than 8 d, an area that could hold more than kMaxSamplerPoints points, and non-positive
// baseline parameters; OUT_OF_RANGE for a coordinate beyond 2^32 d, where rounding would eat the
// spacing margin.
Status ValidateSamplerOptions(const SamplerOptions& options);

// Validates, then samples. Pure: the same options give the same bits.
// On a rectangle every point lies in the half-open rectangle; on a torus every
// point lies in the rectangle and distances are measured with wrap-around.
// Every pair satisfies (dx^2 + dy^2) >= d^2 evaluated in double precision.
StatusOr<std::vector<Vec2>> Sample(const SamplerOptions& options);

}  // namespace scallop
