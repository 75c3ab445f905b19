// SamplingProblem: what each sampler receives once the options are valid.
// Shared by the bounded samplers and the infinite-plane engine, which passes
// the final points of neighbouring regions as fixed points.
#pragma once

#include <algorithm>
#include <cmath>
#include <span>

#include "scallop/geometry/rect.h"
#include "scallop/geometry/vec2.h"
#include "scallop/sampling/sampler.h"

namespace scallop {

struct SamplingProblem {
  Domain domain;
  double min_distance = 1.0;
  // r' / 2r for A1 and A2.
  double density = 2.0;
  // Points placed earlier outside the domain (rectangles only, within 2 d of
  // it): new points keep d from them, and they seed neighbourhoods. Never
  // returned. When empty, the sampler starts from one uniform point.
  std::span<const Vec2> fixed_points;
};

// The largest |coordinate| a problem's points can have, for SpacingFor.
inline double MaxAbsCoordinate(const SamplingProblem& problem, double margin) {
  const Rect& r = problem.domain.rect;
  return std::max(std::max(std::abs(r.x0), std::abs(r.x1)),
                  std::max(std::abs(r.y0), std::abs(r.y1))) + margin;
}

// True when no fixed point lies within `reach` of the domain, so a sampler
// must start from a uniform point of its own: its neighbourhoods (radius
// `reach` about each point) would otherwise never enter the domain.
inline bool NeedsSeedPoint(const SamplingProblem& problem, double reach) {
  const Rect& r = problem.domain.rect;
  for (const Vec2& p : problem.fixed_points) {
    const double dx = std::max({r.x0 - p.x, 0.0, p.x - r.x1});
    const double dy = std::max({r.y0 - p.y, 0.0, p.y - r.y1});
    if (dx * dx + dy * dy < reach * reach) return false;
  }
  return true;
}

}  // namespace scallop
