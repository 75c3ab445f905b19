// A3 implementation: a grid of points, a pool of candidates picked uniformly
// at random, and for each candidate its available boundary, computed once
// from its neighbours and then consumed by placing points on it.
#include "scallop/sampling/boundary_sampler.h"

#include <algorithm>
#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "scallop/sampling/available_boundary.h"
#include "scallop/sampling/boundary_grid.h"
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

// {sqrt(t[0]), sqrt(t[1])}: one packed square root where SSE2 has it (the
// same correctly rounded bits), where std::sqrt gave two, each behind a
// branch that keeps errno for negative inputs (t >= 0 here).
Doubles SquareRoots(Doubles t) {
#if defined(__SSE2__)
  return _mm_sqrt_pd(t);
#else
  return Doubles{std::sqrt(t[0]), std::sqrt(t[1])};
#endif
}

// The arc of the candidate's circle (radius s) that the disk of radius s
// about a neighbour at `offset` (|offset| < 2 s) covers, as the keys
// (pseudo-angles) of its ends.
struct Arc {
  double from_key, to_key;
};

// The arcs that the neighbours at offset0 and offset1 from the candidate
// cover, into arcs[0] and arcs[1]. Each is centred on the direction
// o = offset, with ends along o -+ k o', k = sqrt(4 s^2 / D^2 - 1). Both at
// once, in the two lanes of SSE2 registers: the divisions and square roots
// are most of A3's arithmetic.
void CoveredArcs(Vec2 offset0, Vec2 offset1, double spacing_squared, Arc* arcs) {
  const Doubles x = {offset0.x, offset1.x}, y = {offset0.y, offset1.y};
  const Doubles four_s2 = {4 * spacing_squared, 4 * spacing_squared};
  const Doubles t = four_s2 / (x * x + y * y) - 1.0;
  const Doubles k = SquareRoots(t);
  // o' = (-y, x); from = o - k o', to = o + k o'.
  const Doubles from_key = PseudoAngles(x + k * y, y - k * x);
  const Doubles to_key = PseudoAngles(x - k * y, y + k * x);
  for (int lane = 0; lane < 2; ++lane) arcs[lane] = {from_key[lane], to_key[lane]};
}

// The arc of the candidate's circle that a point placed on it, in direction
// `direction` (any length), covers with its disk: half-width pi/3 about it.
// Rotating by -+60 degrees needs no trigonometry: cos = 1/2, sin = sqrt(3)/2.
Arc PlacedArc(Vec2 direction) {
  constexpr double kSin60 = 0.86602540378443864676372317075294;
  const Vec2 half = 0.5 * direction, turned = {-kSin60 * direction.y, kSin60 * direction.x};
  const Doubles keys = PseudoAngles(Doubles{half.x - turned.x, half.x + turned.x},
                                    Doubles{half.y - turned.y, half.y + turned.y});
  return {keys[0], keys[1]};
}

// A key interval this wide (about a draw's key) is given up when a placement
// there fails the double-precision checks: a rounding sliver.
constexpr double kRejectedKeyWidth = 1e-12;

// SampleBoundary with `grid`, empty, covering the domain (a torus) or the
// domain grown by 2 d + spacing (a rectangle): PointGrid, or on a rectangle
// BoundaryGrid, which holds the same cells in less memory.
template <typename Grid>
std::vector<Vec2> SampleWith(const SamplingProblem& problem, double spacing, Grid& grid, Rng& rng,
                             std::vector<bool>* unprocessed) {
  const Domain& domain = problem.domain;
  const double d = problem.min_distance;
  const double spacing_squared = spacing * spacing;
  const double d_squared = d * d;
  // Placements failing the double-precision checks in a row before the
  // candidate's boundary is given up as rounding slivers.
  constexpr int kMaxRejectedPlacements = 64;

  // Room for as many points as a maximal set of the domain holds (A3 packs
  // 0.86 / d^2), up to 2^22: growing by doubling copied them over and over,
  // and touched twice the memory.
  const double expected = 0.9 * domain.rect.Width() * domain.rect.Height() / d_squared;
  std::vector<Vec2> points;
  points.reserve(problem.inert_points.size() + problem.fixed_points.size() +
                 static_cast<size_t>(std::min(expected, 0x1p22)));
  points.assign(problem.inert_points.begin(), problem.inert_points.end());
  for (size_t i = 0; i < points.size(); ++i) grid.Insert(static_cast<int32_t>(i), points[i]);
  points.insert(points.end(), problem.fixed_points.begin(), problem.fixed_points.end());
  const size_t fixed_count = points.size();
  // Each candidate's position with its index: the pool is small and stays in
  // cache, while `points` grows to N (a cache miss per pick at 1M).
  struct Candidate {
    Vec2 position;
    int32_t index;
  };
  std::vector<Candidate> candidates;
  // With a stop rectangle: how many candidates whose circle reaches it are
  // left. Once none is, every circle there is consumed, so the rectangle is
  // covered (F1 is continuous: an uncovered spot would put a spot at
  // distance exactly `spacing` from a point, on an unconsumed circle).
  const std::optional<Rect>& stop = problem.stop_when_covered;
  auto reaches_stop = [&](Vec2 p) { return stop && SquaredDistance(*stop, p) <= spacing_squared; };
  int64_t pending_near_stop = 0;
  auto add_candidate = [&](int32_t index, Vec2 p) {
    grid.Insert(index, p);
    candidates.push_back({p, index});
    pending_near_stop += reaches_stop(p);
  };
  for (size_t i = problem.inert_points.size(); i < fixed_count; ++i) {
    add_candidate(static_cast<int32_t>(i), points[i]);
  }
  auto add_point = [&](Vec2 p) {
    const auto index = static_cast<int32_t>(points.size());
    points.push_back(p);
    add_candidate(index, p);
  };
  if (NeedsSeedPoint(problem, spacing)) add_point(SeedPoint(problem, rng));

  AvailableBoundary boundary;
  // Neighbours of the candidate, as images near it: nearby[0, nearby_count).
  std::vector<Vec2> nearby;
  size_t nearby_count = 0;
  std::vector<Arc> arcs;  // arcs[k]: the arc nearby[k] covers
  while (!candidates.empty() && !(stop && pending_near_stop == 0)) {
    // Uniform choice among candidates, as the paper prescribes.
    const size_t pick = rng.Below(candidates.size());
    const auto [p, index] = candidates[pick];
    candidates[pick] = candidates.back();
    candidates.pop_back();
    pending_near_stop -= reaches_stop(p);

    boundary.Reset();
    if (!domain.torus) ClipToRectangle(domain.rect, p, spacing, boundary);
    nearby_count = grid.GatherNear(p, 2 * spacing, 4 * spacing_squared, index, nearby);
    // The arcs first, the subtractions after: the arcs' divisions and square
    // roots then overlap instead of each waiting for the cut before it.
    if (arcs.size() < nearby_count + 1) arcs.resize(nearby_count + 1);
    for (size_t n = 0; n < nearby_count; n += 2) {
      // An odd count repeats the last neighbour in the spare lane.
      const Vec2 second = nearby[std::min(n + 1, nearby_count - 1)];
      CoveredArcs(nearby[n] - p, second - p, spacing_squared, &arcs[n]);
    }
    for (size_t n = 0; n < nearby_count && !boundary.empty(); ++n) {
      // Once nothing is left the rest of the neighbours cannot matter.
      const Arc& arc = arcs[n];
      boundary.SubtractArc(arc.from_key, arc.to_key);
    }

    int rejected = 0;  // in a row
    while (!boundary.empty()) {
      const auto [direction, key] = boundary.SampleDirection(rng);
      const double scale = spacing / std::sqrt(SquaredLength(direction));
      const Vec2 x = grid.WrapIntoDomain(p + scale * direction);
      // The margin in `spacing` makes these checks pass; they stay because the
      // contract is promised on the returned doubles, not on an argument.
      bool valid = (domain.torus || domain.rect.Contains(x)) && !InCoveredRect(problem, x);
      for (size_t k = 0; valid && k < nearby_count; ++k) {
        valid = SquaredDistance(grid.NearestImage(x, nearby[k]), x) >= d_squared;
      }
      valid = valid && SquaredDistance(grid.NearestImage(x, p), x) >= d_squared;
      if (!valid) {
        // Give up this key (and a rounding-sized neighbourhood of it). Only
        // rounding slivers fail; should a whole arc ever fail, the candidate
        // is given up rather than drawn from forever.
        const double from = key - kRejectedKeyWidth, to = key + kRejectedKeyWidth;
        boundary.SubtractArc(from < 0 ? from + kFullTurnKey : from,
                             to > kFullTurnKey ? to - kFullTurnKey : to);
        if (++rejected == kMaxRejectedPlacements) boundary.Clear();
        continue;
      }
      rejected = 0;
      add_point(x);
      if (nearby_count == nearby.size()) nearby.push_back(x);
      nearby[nearby_count++] = x;
      // Only the arc of x's disk at distance exactly `spacing` from the
      // candidate is removed: half-width acos(1/2) = pi/3.
      const Arc placed = PlacedArc(direction);
      boundary.SubtractArc(placed.from_key, placed.to_key);
    }
  }
  if (unprocessed) {
    unprocessed->assign(points.size() - fixed_count, false);
    for (const auto& [position, index] : candidates) {
      if (static_cast<size_t>(index) >= fixed_count) (*unprocessed)[index - fixed_count] = true;
    }
  }
  points.erase(points.begin(), points.begin() + static_cast<std::ptrdiff_t>(fixed_count));
  return points;
}

}  // namespace

std::vector<Vec2> SampleBoundary(const SamplingProblem& problem, Rng& rng,
                                 std::vector<bool>* unprocessed) {
  const Domain& domain = problem.domain;
  const double d = problem.min_distance;
  const double reach = 2.0 * d;  // fixed points lie within 2 d of the domain
  const double spacing = SpacingFor(d, MaxAbsCoordinate(problem, domain.torus ? 0.0 : reach));
  if (domain.torus) {
    PointGrid grid(domain.rect, true, d);
    return SampleWith(problem, spacing, grid, rng, unprocessed);
  }
  BoundaryGrid grid(domain.rect, d, reach + spacing);
  return SampleWith(problem, spacing, grid, rng, unprocessed);
}

}  // namespace scallop
