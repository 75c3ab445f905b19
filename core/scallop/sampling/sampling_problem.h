// SamplingProblem: what each sampler receives once the options are valid.
// Shared by the bounded samplers and the infinite-plane engine, which passes
// the final points of neighbouring regions as fixed points.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>

#include "scallop/geometry/rect.h"
#include "scallop/geometry/vec2.h"
#include "scallop/random/rng.h"
#include "scallop/sampling/sampler.h"

namespace scallop {

// A disk no new point may enter: a point of an earlier layer of a layered world and the
// distance D the layer being sampled keeps from it (docs/design.md, "Layers"). A spot x is
// excluded when dx^2 + dy^2 < radius^2 in doubles, the verifier's expression.
struct ExclusionDisk {
  Vec2 centre;
  double radius = 0.0;
};

struct SamplingProblem {
  Domain domain;
  double min_distance = 1.0;
  // r' / 2r for A1 and A2.
  double density = 2.0;
  // Points placed earlier (rectangles only), inside the domain or within 2 d
  // of it: new points keep d from them, and they seed neighbourhoods. Never
  // returned. When empty, the sampler starts from one uniform point.
  std::span<const Vec2> fixed_points;
  // Points placed earlier that only constrain, because they cannot seed
  // anything: their whole neighbourhood (radius r' for A1 and A2, the
  // spacing for A3) lies in covered_rects, or (A3) an earlier run consumed
  // their circle. Skipping them is what makes a plane region cost its new
  // points, not the points around it. Never returned.
  std::span<const Vec2> inert_points;
  // Rectangles the fixed and inert points already cover (no spot in them is
  // farther than the spacing from one): no new point may land in them. A
  // guard against rounding only, since nothing there is available anyway.
  std::span<const Rect> covered_rects;
  // When set (a rectangle inside the domain), sampling stops as soon as it
  // is covered: no spot of it farther than the spacing from a point. The
  // points are then a prefix of the full run: the rectangle and a rim of
  // the domain around it, ending in the run's natural growth front.
  std::optional<Rect> stop_when_covered;
  // When set (inside the domain), where the first point is drawn from if no
  // fixed point seeds the domain.
  std::optional<Rect> seed_area;
  // Disks no new point may enter, and whose spots need no cover: the earlier layers of a
  // layered world. Any order. Taken by A3 on rectangles (SampleBoundary: cut from the circles,
  // and their own circles processed) and by field runs (SampleFieldProblem: masked); the other
  // samplers ignore them.
  std::span<const ExclusionDisk> exclusions;
};

// True when `p` may not be a new point because a covered rectangle holds it.
inline bool InCoveredRect(const SamplingProblem& problem, Vec2 p) {
  for (const Rect& r : problem.covered_rects) {
    if (r.Contains(p)) return true;
  }
  return false;
}

// The largest |coordinate| a problem's points can have, for SpacingFor.
inline double MaxAbsCoordinate(const SamplingProblem& problem, double margin) {
  const Rect& r = problem.domain.rect;
  return std::max(std::max(std::abs(r.x0), std::abs(r.x1)),
                  std::max(std::abs(r.y0), std::abs(r.y1))) +
         margin;
}

// True when no fixed point lies within `reach` of the domain, so a sampler
// must start from a uniform point of its own: its neighbourhoods (radius
// `reach` about each point) would otherwise never enter the domain.
inline bool NeedsSeedPoint(const SamplingProblem& problem, double reach) {
  for (const Vec2& p : problem.fixed_points) {
    if (SquaredDistance(problem.domain.rect, p) < reach * reach) return false;
  }
  return true;
}

// The point a sampler starts from when NeedsSeedPoint: uniform in seed_area
// when set, else in the domain.
inline Vec2 SeedPoint(const SamplingProblem& problem, Rng& rng) {
  const Rect& r = problem.seed_area ? *problem.seed_area : problem.domain.rect;
  const double x = rng.Uniform(r.x0, r.x1);
  return {x, rng.Uniform(r.y0, r.y1)};
}

}  // namespace scallop
