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
// arcs that fall outside the half-open rectangle: beyond an edge at distance
// a along outward normal n, the arc from a n - h n' to a n + h n'
// (counterclockwise, n' = n turned left, h = sqrt(radius^2 - a^2)).
void ClipToRectangle(const Rect& rect, Vec2 centre, double radius, AvailableBoundary& boundary) {
  const struct {
    Vec2 normal;
    double distance;
  } edges[4] = {{{1, 0}, rect.x1 - centre.x},
                {{0, 1}, rect.y1 - centre.y},
                {{-1, 0}, centre.x - rect.x0},
                {{0, -1}, centre.y - rect.y0}};
  for (const auto& [n, a] : edges) {
    if (a >= radius) continue;
    if (a <= -radius) {
      boundary.Clear();
      return;
    }
    const double h = std::sqrt(radius * radius - a * a);
    const Vec2 left{-n.y, n.x};
    boundary.SubtractArc(a * n - h * left, a * n + h * left);
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
      // Once nothing is left the rest of the neighbours cannot matter.
      if (other == index || boundary.empty()) return;
      const Vec2 offset = q - p;
      const double distance_squared = SquaredLength(offset);
      if (distance_squared >= 4 * spacing_squared) return;
      nearby.push_back(q);
      // q's disk of radius s covers the arc of p's circle centred on the
      // direction o = q - p with ends along o -+ k o', k = sqrt(4 s^2 / D^2 - 1).
      const double k = std::sqrt(4 * spacing_squared / distance_squared - 1.0);
      const Vec2 left{-offset.y, offset.x};
      boundary.SubtractArc(offset - k * left, offset + k * left);
    });
    boundary.Finish();

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
