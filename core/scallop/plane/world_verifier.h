// Verifies the contract on a rectangle of a world: the rectangle's points plus
// a halo of 2 d go through the Delaunay verifier, with pairs across region
// seams counted apart. What `scallop verify` and the Verify RPC run.
#pragma once

#include <functional>

#include "scallop/plane/plane_engine.h"
#include "scallop/plane/query_rect.h"
#include "scallop/verify/delaunay_verifier.h"

namespace scallop {

// The maximality tolerance for a window whose coordinates reach `max_abs`:
// the samplers' spacing margin there (sampling/spacing.h), doubled for the
// rounding of circumcentres, and never below the verifier's default.
double MaximalityTolerance(double min_distance, double max_abs);

// Verifies `rect` of `world`: spacing for every pair with an end inside,
// maximality for every spot inside. A radius-field world is judged by the
// field verifier (VerifyFieldWindow: the max rule, G measured against R at
// each spot, masks excluded), its report in VerifyReport::field. What it
// reads is the rectangle grown by a 2 d halo (2 r_max for a field world), so
// the rectangle rule (query_rect.h) applies to both: `rect`'s bounds, then
// the grown rectangle's bounds (OUT_OF_RANGE within 2 d of the limit) and its
// cost under `limit`, named "rect+halo" in messages. A layered world is judged
// by the layered verifier (VerifyLayeredWindow: every pair under the exclusion
// matrix, each layer maximal given the others), its report in
// VerifyReport::layered, with a halo of max(2 largest spacing, largest D).
// REQUIRES: the engine's max_query_area >= limit.max_area.
// With `inside`, also the world's points in `rect`, in query order, for
// callers that go on to measure them (scallop analyze).
// With `stop`, the verifier (Delaunay or field) polls it and returns
// CANCELLED once it says so (its caller has gone); the query before it is
// for the caller to stop.
// Cost: one query of the grown rectangle plus O(N log N) for the verifier.
StatusOr<VerifyReport> VerifyWorldRect(PlaneEngine& engine, const World& world, const Rect& rect,
                                       const QueryLimit& limit, PlanePoints* inside = nullptr,
                                       std::function<bool()> stop = nullptr);

}  // namespace scallop
