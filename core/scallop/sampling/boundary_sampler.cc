// A3 implementation: a grid of points, a pool of candidates picked uniformly
// at random, and for each candidate its available boundary, computed once
// from its neighbours (first by bins, then exactly where bins are left) and
// then consumed by placing points on it.
#include "scallop/sampling/boundary_sampler.h"

#include <algorithm>
#include <cmath>
#include <span>
#include <type_traits>

#include "scallop/geometry/rect_distance.h"
#include "scallop/sampling/available_boundary.h"
#include "scallop/sampling/boundary_arcs.h"
#include "scallop/sampling/boundary_exclusions.h"
#include "scallop/sampling/boundary_grid.h"
#include "scallop/sampling/boundary_scratch.h"
#include "scallop/sampling/candidate_boundary.h"
#include "scallop/sampling/point_grid.h"
#include "scallop/sampling/spacing.h"

namespace scallop {
namespace {

// Whether the circle of radius `radius` about `centre` lies inside the rectangle: four
// comparisons settle most circles, without the call of ClipToRectangle.
bool CircleInside(const Rect& rect, Vec2 centre, double radius) {
  return std::min(centre.x - rect.x0, rect.x1 - centre.x) >= radius &&
         std::min(centre.y - rect.y0, rect.y1 - centre.y) >= radius;
}

// Appends to `arcs` the arcs of the circle of radius `radius` about `centre`
// that fall outside the half-open rectangle: beyond an edge at distance a
// along outward normal n, the arc from a n - h n' to a n + h n'
// (counterclockwise, n' = n turned left, h = sqrt(radius^2 - a^2)). Returns
// false, appending nothing more, when the whole circle is outside.
[[gnu::noinline]] bool ClipToRectangle(const Rect& rect, Vec2 centre, double radius,
                                       std::vector<KeyArc>& arcs) {
  if (CircleInside(rect, centre, radius)) return true;
  const struct {
    Vec2 normal;
    double distance;
  } edges[4] = {{{1, 0}, rect.x1 - centre.x},
                {{0, 1}, rect.y1 - centre.y},
                {{-1, 0}, centre.x - rect.x0},
                {{0, -1}, centre.y - rect.y0}};
  for (const auto& [n, a] : edges) {
    if (a >= radius) continue;
    if (a <= -radius) return false;
    const double h = std::sqrt(radius * radius - a * a);
    const Vec2 left{-n.y, n.x};
    arcs.push_back({PseudoAngle(a * n - h * left), PseudoAngle(a * n + h * left)});
  }
  return true;
}

// Whether every point of `points` is at least sqrt(limit_squared) from x:
// two at a time in SSE2 lanes, without a branch per point.
bool FarFromAll(Vec2 x, const Vec2* points, size_t count, double limit_squared) {
  Doubles nearest = {INFINITY, INFINITY};
  const Doubles px = {x.x, x.x}, py = {x.y, x.y};
  size_t k = 0;
  for (; k + 1 < count; k += 2) {
    const Doubles dx = Doubles{points[k].x, points[k + 1].x} - px;
    const Doubles dy = Doubles{points[k].y, points[k + 1].y} - py;
    const Doubles squared = dx * dx + dy * dy;
    nearest = squared < nearest ? squared : nearest;
  }
  bool far = nearest[0] >= limit_squared && nearest[1] >= limit_squared;
  if (k < count) far = far && SquaredDistance(points[k], x) >= limit_squared;
  return far;
}

// A key interval this wide (about a draw's key) is given up when a placement
// there fails the double-precision checks: a rounding sliver.
constexpr double kRejectedKeyWidth = 1e-12;
// Placements failing the double-precision checks in a row before the
// candidate's boundary is given up as rounding slivers.
constexpr int kMaxRejectedPlacements = 64;

// Gives up a key whose placement failed the double-precision checks (and a
// rounding-sized neighbourhood of it). Only rounding slivers fail; should a
// whole arc ever fail, the boundary is given up rather than drawn from
// forever. `rejected` counts failures in a row.
void RejectKey(double key, int& rejected, AvailableBoundary& boundary) {
  const double from = key - kRejectedKeyWidth, to = key + kRejectedKeyWidth;
  boundary.SubtractArc(from < 0 ? from + kFullTurnKey : from,
                       to > kFullTurnKey ? to - kFullTurnKey : to);
  if (++rejected == kMaxRejectedPlacements) boundary.Clear();
}

// Settles a draw at `key` placed at x: gives the key up when x failed the double-precision
// checks, or else adds x (add_point) and among the circle's neighbours, nearby[0,
// nearby_count). Returns whether x was placed.
template <typename AddPoint>
bool Settle(bool valid, Vec2 x, double key, int& rejected, AvailableBoundary& boundary,
            AddPoint& add_point, std::vector<Vec2>& nearby, size_t& nearby_count) {
  if (!valid) {
    RejectKey(key, rejected, boundary);
    return false;
  }
  rejected = 0;
  add_point(x);
  if (nearby_count == nearby.size()) nearby.push_back(x);
  nearby[nearby_count++] = x;
  return true;
}

// Processes the circle of exclusion disk `disk` (its cut radius) as A3 processes a point's:
// its part inside `area` less the arcs the points' disks (radius `spacing`) and the other
// exclusion disks cover, then points placed on what is left until nothing is, each added by
// add_point. `grid` holds every point. Scratch: nearby, arcs, candidate_boundary, boundary.
template <typename Grid, typename AddPoint>
void PlaceOnDiskCircle(const SamplingProblem& problem, double spacing,
                       BoundaryExclusions& exclusions, uint32_t disk, const Rect& area,
                       const Grid& grid, Rng& rng, std::vector<Vec2>& nearby,
                       std::vector<KeyArc>& arcs, CandidateBoundary& candidate_boundary,
                       AvailableBoundary& boundary, AddPoint add_point) {
  const Vec2 c = exclusions.centre(disk);
  const double radius = exclusions.cut_radius(disk);
  const double reach = radius + spacing;
  size_t nearby_count = grid.GatherNear(c, reach, reach * reach, -1, nearby);
  // Most circles are covered by the points' disks alone, whatever the rectangle clips: settled
  // before the clip and the boundary are computed (no draw is made either way).
  if (!exclusions.GatherAroundDisk(disk, std::span(nearby.data(), nearby_count))) return;
  arcs.clear();
  if (!ClipToRectangle(area, c, radius, arcs)) return;
  candidate_boundary.Build(c, arcs, {}, boundary);
  exclusions.CutGatheredDisk(disk, boundary);
  const double d_squared = problem.min_distance * problem.min_distance;
  int rejected = 0;  // in a row
  while (!boundary.empty()) {
    const auto [direction, key] = boundary.SampleDirection(rng);
    const Vec2 x = c + (radius / std::sqrt(SquaredLength(direction))) * direction;
    // The checks of a point's circle; x's distance to c is the cut radius, above D.
    const bool valid = problem.domain.rect.Contains(x) && !InCoveredRect(problem, x) &&
                       FarFromAll(x, nearby.data(), nearby_count, d_squared) &&
                       !exclusions.Excludes(x);
    if (!Settle(valid, x, key, rejected, boundary, add_point, nearby, nearby_count)) continue;
    KeyArc placed;
    const DiskCover cover = CoveredArcOfCircle(x - c, radius, spacing, placed);
    if (cover == DiskCover::kWhole) boundary.Clear();
    if (cover == DiskCover::kArc) boundary.SubtractArc(placed.from_key, placed.to_key);
  }
}

// SampleBoundary with `grid`, empty, covering the domain (a torus) or the
// domain grown by 2 d + spacing (a rectangle): PointGrid, or on a rectangle
// BoundaryGrid, which holds the same cells in less memory. Works in
// `scratch`'s lists; with `keep_scratch`, returns a copy of the new points
// and leaves the lists their memory, else returns the list itself.
template <typename Grid>
std::vector<Vec2> SampleWith(const SamplingProblem& problem, double spacing,
                             BoundaryExclusions& exclusions, Grid& grid, Rng& rng,
                             std::vector<bool>* unprocessed, BoundaryScratch& scratch,
                             bool keep_scratch) {
  const Domain& domain = problem.domain;
  const double d = problem.min_distance;
  const double spacing_squared = spacing * spacing;
  const double d_squared = d * d;

  // Room for as many points as a maximal set of the domain holds (A3 packs
  // 0.86 / d^2), up to 2^22: growing by doubling copied them over and over,
  // and touched twice the memory.
  const double expected = 0.9 * domain.rect.Width() * domain.rect.Height() / d_squared;
  std::vector<Vec2>& points = scratch.points;
  points.reserve(problem.inert_points.size() + problem.fixed_points.size() +
                 static_cast<size_t>(std::min(expected, 0x1p22)));
  points.assign(problem.inert_points.begin(), problem.inert_points.end());
  for (size_t i = 0; i < points.size(); ++i) grid.Insert(static_cast<int32_t>(i), points[i]);
  points.insert(points.end(), problem.fixed_points.begin(), problem.fixed_points.end());
  const size_t fixed_count = points.size();
  // Each candidate's position with its index: the pool is small and stays in
  // cache, while `points` grows to N (a cache miss per pick at 1M).
  std::vector<BoundaryCandidate>& candidates = scratch.candidates;
  candidates.clear();
  // With a stop rectangle: how many candidates whose circle reaches it are
  // left. Once none is, every circle there is consumed, so the rectangle is
  // covered (F1 is continuous: an uncovered spot would put a spot at
  // distance exactly `spacing` from a point, on an unconsumed circle).
  const std::optional<Rect>& stop = problem.stop_when_covered;
  auto reaches_stop = [&](Vec2 p) {
    return stop && SquaredDistanceInLanes(*stop, p) <= spacing_squared;
  };
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
  if (NeedsSeedPoint(problem, spacing)) {
    // A seed inside an exclusion disk is dropped: the disks' circles seed the growth (below).
    const Vec2 seed = SeedPoint(problem, rng);
    if (!exclusions.AnyExcludes(seed)) add_point(seed);
  }

  AvailableBoundary& boundary = scratch.boundary;
  // Neighbours of the candidate, as images near it: nearby[0, nearby_count).
  std::vector<Vec2>& nearby = scratch.nearby;
  size_t nearby_count = 0;
  // Of the candidate's circle, outside the rectangle.
  std::vector<KeyArc>& outside_arcs = scratch.outside_arcs;
  if (scratch.candidate_boundary) {
    scratch.candidate_boundary->Reset(spacing);
  } else {
    scratch.candidate_boundary.emplace(spacing);
  }
  CandidateBoundary& candidate_boundary = *scratch.candidate_boundary;
  // The exclusion disks whose circle is still to be processed: those that reach the stop
  // rectangle (or the domain), each once, after the points' circles there (below).
  std::vector<uint32_t>& pockets = scratch.pockets;
  const Rect& pocket_area = stop ? *stop : domain.rect;
  // Filed without a branch each: about a third of a region's disks reach its stop rectangle,
  // which no branch predicts.
  pockets.resize(exclusions.size() + 1);
  size_t pocket_count = 0;
  for (size_t k = 0; k < exclusions.size(); ++k) {
    const double r = exclusions.cut_radius(k);
    pockets[pocket_count] = static_cast<uint32_t>(k);
    pocket_count += SquaredDistanceInLanes(pocket_area, exclusions.centre(k)) <= r * r;
  }
  pockets.resize(pocket_count);
  while (true) {
    if (candidates.empty() || (stop && pending_near_stop == 0)) {
      // Every point's circle near the stop rectangle is processed. A spot there that is still
      // free (farther than `spacing` from every point, outside every disk) with no free spot of
      // a point's circle around it lies in a pocket that exclusion disks close, and a pocket's
      // edge is a disk's circle: process those, uniformly in turn, placing on the part inside
      // the stop rectangle (or domain) only, so that nothing is placed ahead of the growth
      // front. Points placed there are candidates, and the growth resumes from them.
      if (pockets.empty()) break;
      const size_t pick = rng.Below(pockets.size());
      const uint32_t disk = pockets[pick];
      pockets[pick] = pockets.back();
      pockets.pop_back();
      PlaceOnDiskCircle(problem, spacing, exclusions, disk, pocket_area, grid, rng, nearby,
                        outside_arcs, candidate_boundary, boundary, add_point);
      continue;
    }
    // Uniform choice among candidates, as the paper prescribes.
    const size_t pick = rng.Below(candidates.size());
    const auto [p, index] = candidates[pick];
    candidates[pick] = candidates.back();
    candidates.pop_back();
    pending_near_stop -= reaches_stop(p);

    outside_arcs.clear();
    const bool inside = domain.torus || CircleInside(domain.rect, p, spacing) ||
                        ClipToRectangle(domain.rect, p, spacing, outside_arcs);
    nearby_count = grid.GatherNear(p, 2 * spacing, 4 * spacing_squared, index, nearby);
    if (inside && exclusions.empty()) {
      candidate_boundary.Build(p, outside_arcs, std::span(nearby.data(), nearby_count), boundary);
    } else if (inside && exclusions.GatherAroundPoint(p)) {
      // The disks' whole bins go with the points' (no point's arc is computed for a bin a disk
      // covers), their exact arcs after the points' (most circles have nothing left by then).
      candidate_boundary.Build(p, outside_arcs, std::span(nearby.data(), nearby_count), boundary,
                               exclusions.GatheredCoveredBins());
      if (!boundary.empty()) exclusions.CutGathered(boundary);
    } else {
      boundary.Clear();
    }

    int rejected = 0;  // in a row
    while (!boundary.empty()) {
      const auto [direction, key] = boundary.SampleDirection(rng);
      const double scale = spacing / std::sqrt(SquaredLength(direction));
      const Vec2 x = grid.WrapIntoDomain(p + scale * direction);
      // The margin in `spacing` makes these checks pass; they stay because the
      // contract is promised on the returned doubles, not on an argument.
      bool valid = (domain.torus || domain.rect.Contains(x)) && !InCoveredRect(problem, x);
      if constexpr (std::is_same_v<Grid, BoundaryGrid>) {
        valid = valid && FarFromAll(x, nearby.data(), nearby_count, d_squared);
      } else {  // a torus: each neighbour's image nearest x
        for (size_t k = 0; valid && k < nearby_count; ++k) {
          valid = SquaredDistance(grid.NearestImage(x, nearby[k]), x) >= d_squared;
        }
      }
      valid = valid && SquaredDistance(grid.NearestImage(x, p), x) >= d_squared;
      valid = valid && !(!exclusions.empty() && exclusions.Excludes(x));
      if (!Settle(valid, x, key, rejected, boundary, add_point, nearby, nearby_count)) continue;
      // Only the arc of x's disk at distance exactly `spacing` from the
      // candidate is removed: half-width acos(1/2) = pi/3.
      const KeyArc placed = PlacedArc(direction);
      boundary.SubtractArc(placed.from_key, placed.to_key);
    }
  }
  if (unprocessed) {
    unprocessed->assign(points.size() - fixed_count, false);
    for (const auto& [position, index] : candidates) {
      if (static_cast<size_t>(index) >= fixed_count) (*unprocessed)[index - fixed_count] = true;
    }
  }
  if (keep_scratch) {
    return {points.begin() + static_cast<std::ptrdiff_t>(fixed_count), points.end()};
  }
  points.erase(points.begin(), points.begin() + static_cast<std::ptrdiff_t>(fixed_count));
  return std::move(points);
}

}  // namespace

std::vector<Vec2> SampleBoundary(const SamplingProblem& problem, Rng& rng,
                                 std::vector<bool>* unprocessed, BoundaryScratch* scratch) {
  const Domain& domain = problem.domain;
  const double d = problem.min_distance;
  const double reach = 2.0 * d;  // fixed points lie within 2 d of the domain
  const double max_abs = MaxAbsCoordinate(problem, domain.torus ? 0.0 : reach);
  const double spacing = SpacingFor(d, max_abs);
  BoundaryScratch own_scratch;
  const bool keep_scratch = scratch != nullptr;
  if (!keep_scratch) scratch = &own_scratch;
  // Exclusion disks are a plane region's (rectangles only): a torus gets none.
  BoundaryExclusions& exclusions = scratch->exclusions;
  exclusions.Reset(domain.torus ? std::span<const ExclusionDisk>{} : problem.exclusions, d, spacing,
                   max_abs);
  if (domain.torus) {
    PointGrid grid(domain.rect, true, d);
    return SampleWith(problem, spacing, exclusions, grid, rng, unprocessed, *scratch, keep_scratch);
  }
  if (scratch->grid) {
    scratch->grid->Reset(domain.rect, d, reach + spacing);
  } else {
    scratch->grid.emplace(domain.rect, d, reach + spacing);
  }
  return SampleWith(problem, spacing, exclusions, *scratch->grid, rng, unprocessed, *scratch,
                    keep_scratch);
}

}  // namespace scallop
