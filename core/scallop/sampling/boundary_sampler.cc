// A3 implementation: a grid of points, a pool of candidates picked uniformly
// at random, and for each candidate its available boundary, computed once
// from its neighbours and then consumed by placing points on it.
#include "scallop/sampling/boundary_sampler.h"

#include <cmath>

#include "scallop/sampling/available_boundary.h"
#include "scallop/sampling/point_grid.h"
#include "scallop/sampling/spacing.h"

namespace scallop {
namespace {

// Removes from `boundary` (a circle of radius `radius` about `centre`) the
// angles whose point falls outside the half-open rectangle. The circle's
// point at angle t is centre + radius (cos t, sin t).
void ClipToRectangle(const Rect& rect, Vec2 centre, double radius, AvailableBoundary& boundary) {
  // For each edge: the angles where the circle is beyond it form an arc
  // centred on the edge's outward normal, of half-width acos(distance / radius).
  const double distance_to_edge[4] = {rect.x1 - centre.x, rect.y1 - centre.y,
                                      centre.x - rect.x0, centre.y - rect.y0};
  for (int edge = 0; edge < 4; ++edge) {
    const double ratio = distance_to_edge[edge] / radius;
    if (ratio >= 1.0) continue;
    const double half_width = ratio <= -1.0 ? kTwoPi : std::acos(ratio);
    boundary.Subtract(edge * (kTwoPi / 4), half_width);
  }
}

}  // namespace

std::vector<Vec2> SampleBoundary(const SamplingProblem& problem, Rng& rng) {
  const Domain& domain = problem.domain;
  const double d = problem.min_distance;
  const double reach = 2.0 * d;  // fixed points lie within 2 d of the domain
  const double spacing = SpacingFor(d, MaxAbsCoordinate(problem, domain.torus ? 0.0 : reach));
  const double spacing_squared = spacing * spacing;
  const double d_squared = d * d;
  // Only the arc of x's disk at distance exactly `spacing` from the candidate
  // is removed when x is placed: half-width acos(1/2) = pi/3.
  constexpr double kPlacedHalfWidth = kTwoPi / 6;

  PointGrid grid(domain.rect, domain.torus, d, domain.torus ? 0.0 : reach + spacing);
  std::vector<Vec2> points(problem.fixed_points.begin(), problem.fixed_points.end());
  const size_t fixed_count = points.size();
  std::vector<int32_t> candidates;
  for (size_t i = 0; i < fixed_count; ++i) {
    grid.Insert(static_cast<int32_t>(i), points[i]);
    candidates.push_back(static_cast<int32_t>(i));
  }
  auto add_point = [&](Vec2 p) {
    const auto index = static_cast<int32_t>(points.size());
    points.push_back(p);
    grid.Insert(index, p);
    candidates.push_back(index);
  };
  if (NeedsSeedPoint(problem, spacing)) {
    const Rect& r = domain.rect;
    add_point({rng.Uniform(r.x0, r.x1), rng.Uniform(r.y0, r.y1)});
  }

  AvailableBoundary boundary;
  std::vector<Vec2> nearby;  // neighbours of the candidate, as images near it
  while (!candidates.empty()) {
    // Uniform choice among candidates, as the paper prescribes.
    const size_t pick = rng.Below(candidates.size());
    const int32_t index = candidates[pick];
    candidates[pick] = candidates.back();
    candidates.pop_back();
    const Vec2 p = points[static_cast<size_t>(index)];

    boundary.Reset();
    if (!domain.torus) ClipToRectangle(domain.rect, p, spacing, boundary);
    nearby.clear();
    grid.ForEachNear(p, 2 * spacing, [&](int32_t other, Vec2 q) {
      if (other == index) return;
      const Vec2 offset = q - p;
      const double distance_squared = SquaredLength(offset);
      if (distance_squared >= 4 * spacing_squared) return;
      nearby.push_back(q);
      // q's disk of radius `spacing` covers the arc within acos(D / 2s) of q's direction.
      const double distance = std::sqrt(distance_squared);
      boundary.Subtract(std::atan2(offset.y, offset.x), std::acos(distance / (2 * spacing)));
    });

    while (!boundary.empty()) {
      const double angle = boundary.SampleAngle(rng);
      const Vec2 x = grid.WrapIntoDomain(p + spacing * UnitAt(angle));
      // The margin in `spacing` makes these checks pass; they stay because the
      // contract is promised on the returned doubles, not on an argument.
      bool valid = domain.torus || domain.rect.Contains(x);
      for (size_t k = 0; valid && k < nearby.size(); ++k) {
        valid = SquaredDistance(grid.NearestImage(x, nearby[k]), x) >= d_squared;
      }
      valid = valid && SquaredDistance(grid.NearestImage(x, p), x) >= d_squared;
      if (!valid) {
        // Give up this angle (and a rounding-sized neighbourhood of it).
        boundary.Subtract(angle, 1e-12);
        continue;
      }
      add_point(x);
      nearby.push_back(x);
      boundary.Subtract(angle, kPlacedHalfWidth);
    }
  }
  points.erase(points.begin(), points.begin() + static_cast<std::ptrdiff_t>(fixed_count));
  return points;
}

}  // namespace scallop
