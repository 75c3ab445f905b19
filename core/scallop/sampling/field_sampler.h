// Bounded sampling with a radius field (issue 24): points in a rectangle, no two in conflict
// (|p - q| < max(R(p), R(q))), maximal under that rule outside masks. Boundary growth in the
// manner of A3 plus a certified sweep; docs/design.md, "Radius fields", has the argument.
#pragma once

#include <cstdint>
#include <vector>

#include "scallop/base/status.h"
#include "scallop/field/radius_field.h"
#include "scallop/geometry/rect.h"
#include "scallop/geometry/vec2.h"
#include "scallop/random/rng.h"
#include "scallop/sampling/sampling_problem.h"

namespace scallop {

// Largest (width / r_min + 2) (height / r_min + 2) a field domain may have: about 64e6 points
// at most, a few GiB of working memory at the worst, as for the constant-spacing samplers
// (kMaxSamplerPoints). The + 2 bounds long thin domains too, whose grids would otherwise have
// a column per r_min however small their area.
inline constexpr double kMaxFieldDomainCells = 64e6;

// FieldDomainCells(r, r_min) <= kMaxFieldDomainCells is what ValidateFieldSamplerOptions and
// VerifyFieldDomain require.
inline double FieldDomainCells(const Rect& r, double r_min) {
  return (r.Width() / r_min + 2.0) * (r.Height() / r_min + 2.0);
}
// Coordinates up to 2^32 r_min from the origin: beyond, rounding of a coordinate (ulp(M)/2)
// eats the 2^-32 relative padding the growth places points with.
inline constexpr double kMaxFieldCoordinate = 0x1.0p32;

struct FieldSamplerOptions {
  // Half-open [x0, x1) x [y0, y1).
  Rect domain;
  uint64_t seed = 0;
  // Most tries on one candidate's curve. Each try draws a direction from what its neighbours'
  // arcs and its earlier tries left and cuts its own arc, so a candidate runs out of directions
  // long before this (1.1 tries a point placed at r_max / r_min = 8); the cap bounds a
  // candidate whose tries keep meeting masks.
  int curve_tries = 64;
};

// What a run did, for tests and the benchmark.
struct FieldSampleStats {
  int64_t grown = 0;         // points placed on a candidate's curve
  int64_t swept = 0;         // points placed by the sweep (seeds of unreached parts, gaps)
  int64_t cells_tested = 0;  // coverage certificates attempted by the sweep
  int64_t leaves = 0;        // finest sweep cells (near-tangent spots), see kFieldLeafFraction
  int64_t curve_spots = 0;   // spots computed on candidates' curves (tries)
  int64_t evaluations = 0;   // R(x) evaluations, bounds included
};

// The sweep's finest cell side over r_min: spots in a finest cell whose tested spots are all
// covered may be uncovered by at most (1 + L) sqrt(2) 2^-30 r_min (< 2.2e-9 r_min).
inline constexpr double kFieldLeafFraction = 0x1.0p-30;

// Checks the options against the field: INVALID_ARGUMENT for a non-finite, empty or inverted
// domain ("domain"), FieldDomainCells above kMaxFieldDomainCells ("domain"), curve_tries outside
// [1, 64] ("curve_tries"); OUT_OF_RANGE ("domain") for a coordinate beyond
// kMaxFieldCoordinate r_min.
Status ValidateFieldSamplerOptions(const FieldSamplerOptions& options, const RadiusField& field);

// Validates, then samples. Pure: the same options and field give the same bits.
// Guarantees, judged on the returned doubles:
//  - every point lies in the half-open domain and in no masked pixel;
//  - no conflict: for every pair dx^2 + dy^2 >= max(R(p), R(q))^2 (R by RadiusField::Evaluate,
//    the same bits the verifier computes, so no margin is needed for this check);
//  - maximal up to a tolerance: every unmasked spot x of the closed domain has a point q with
//    |x - q| < max(R(x), R(q)) + (1 + L) sqrt(2) 2^-30 r_min (the sweep certifies coverage
//    against R itself, so the growth's 2^-32 placement padding does not enter).
// Cost: O(N) expected for a fixed r_max / r_min; measured at r_max / r_min = 8, per point: 1.1
// curve tries, 7.1 field evaluations, 8.4 sweep cells (docs/performance.md, "Radius fields,
// bounded", for the points a second against uniform A3 and the field Bridson below).
// A constant field is sampled by this algorithm too, so its points differ from Sample's A3:
// worlds with a constant field keep using Sample.
StatusOr<std::vector<Vec2>> SampleField(const FieldSamplerOptions& options,
                                        const RadiusField& field,
                                        FieldSampleStats* stats = nullptr);

// A region of a field world on the plane (plane/region_generator.cc): SampleField's growth and
// sweep on problem.domain.rect (never a torus), with
//  - inert_points: constrain new points (R evaluated at each: R is a pure function of the
//    field, so these are the bits the point was placed with);
//  - fixed_points: constrain, and are the first candidates of the growth, in their order;
//  - covered_rects: closed, no new point lands in them;
//  - stop_when_covered: the growth stops once no candidate whose curve can reach the
//    rectangle (|p - rect| < Pad(R(p) / (1 - L))) is left, and the sweep certifies that
//    rectangle only; without it, the whole domain;
//  - seed_area: when no fixed point lies within r_max / (1 - L) of the domain, up to 64 spots
//    drawn uniformly there are tried as the first point (masks may refuse them all; the
//    sweep then seeds).
// min_distance and density are ignored. Returns the new points in placement order and, with
// `unprocessed`, whether each was still a candidate when the run stopped; advances `rng`.
// Guarantees: no new point conflicts with any point of the run (fixed, inert or new) or lies
// in a mask, a closed rectangle or outside the domain; every spot of the stop rectangle (or
// domain) outside masks is covered, to SampleField's tolerance, by the run's points.
// REQUIRES: the domain is within the field's coordinate limit (kMaxFieldCoordinate r_min, plus
// a few r_max) and FieldDomainCells of it is bounded: the plane's regions are.
std::vector<Vec2> SampleFieldProblem(const SamplingProblem& problem, const RadiusField& field,
                                     Rng& rng, std::vector<bool>* unprocessed,
                                     FieldSampleStats* stats = nullptr);

// Baseline for comparison only: Bridson 2007 with a field, as users have it today. From a
// random active point p, `attempts` uniform darts of the annulus R(p)..2R(p); each is kept when
// in the domain, unmasked and in conflict with no point (the same max rule). Not maximal: it
// leaves gaps and seeds only the part of the domain one seed can reach.
StatusOr<std::vector<Vec2>> SampleFieldBridson(const FieldSamplerOptions& options,
                                               const RadiusField& field, int attempts = 30);

}  // namespace scallop
