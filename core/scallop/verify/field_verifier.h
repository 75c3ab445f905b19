// The verifier for radius fields: judges a bounded point set against the max rule (no pair
// with |p - q| < max(R(p), R(q))) and maximality measured against R at each spot (the largest
// value of G(x) = min_q |x - q| - max(R(x), R(q)) over unmasked spots), with certified bounds.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <span>

#include "scallop/base/status.h"
#include "scallop/field/radius_field.h"
#include "scallop/geometry/rect.h"
#include "scallop/geometry/vec2.h"
#include "scallop/sampling/sampling_problem.h"

namespace scallop {

struct FieldVerifyOptions {
  // maximal_ok is gap_bound < max_tolerance * r_max. The field sampler is maximal up to
  // (1 + L) sqrt(2) 2^-30 r_min (field_sampler.h), and this verifier's own finest cells add
  // (1 + L) 2^-32.5 r_min: together below 3e-9 r_max.
  double max_tolerance = 1e-8;
  // When set, polled every 16,384 steps (a point's pair scan, a cell judged), as the Delaunay
  // verifier polls VerifyOptions::stop: once it returns true the verifier stops and returns
  // CANCELLED (its caller has gone).
  std::function<bool()> stop;
  // Disks whose spots need no cover, as masked pixels need none: for a layer of a layered world,
  // the other layers' points with the distance D kept from each (docs/design.md, "Layers"). G
  // becomes min(G, E) with E(x) = min_c |x - c| - D_c, which has slope 1. Disks within 2 r_max
  // plus the largest D of the domain must be given. The points are not checked against them
  // (the layered verifier counts cross-layer pairs itself).
  std::span<const ExclusionDisk> exclusions;
};

struct FieldVerifyReport {
  int64_t points_checked = 0;
  int64_t points_outside = 0;  // not in the half-open domain
  int64_t points_masked = 0;   // in a masked pixel
  int64_t pairs_checked = 0;   // pairs within r_max of each other, each once
  // Pairs with dx^2 + dy^2 < max(R(p), R(q))^2 in doubles (the sampler's expression).
  int64_t conflicts = 0;
  // The smallest |p - q| / max(R(p), R(q)) over judged pairs, and its pair (input indices).
  double min_spacing_ratio = std::numeric_limits<double>::infinity();
  int64_t closest_index_a = -1, closest_index_b = -1;
  // Largest G found at a probed unmasked spot of the closed domain (a lower bound of the true
  // maximum; +infinity when there are no points) and where.
  double largest_gap = -std::numeric_limits<double>::infinity();
  Vec2 largest_gap_spot;
  // Certified upper bound of G over every unmasked spot of the closed domain.
  double gap_bound = -std::numeric_limits<double>::infinity();

  bool conflict_ok = false;  // conflicts == 0
  bool maximal_ok = false;   // gap_bound < max_tolerance * r_max
  bool passed() const {
    return conflict_ok && maximal_ok && points_outside == 0 && points_masked == 0;
  }
};

// Judges `points` as the output of a field sampler on `domain`.
// Conflicts: every pair closer than r_max, through a grid (no pair farther can conflict), so
// the count is exact. Maximality: cells from side r_max / 2 down; a cell is certified when
// G(centre) + (1 + L) half-diagonal < 0 (G has slope <= 1 + L), fully masked cells are skipped,
// partly masked ones cut at pixel lines; cells are halved down to side r_min 2^-32, and the
// finest cells' bounds enter gap_bound. G(x) is evaluated against the points within 2 r_max
// (farther ones cannot make it negative), an overestimate that keeps the bound valid.
// Rejects (INVALID_ARGUMENT): a non-finite or empty domain, non-finite points, a negative or
// non-finite tolerance, a domain beyond kMaxFieldDomainCells (field_sampler.h). CANCELLED
// when options.stop asked it to stop.
// Cost: O(N (r_max / r_min)^2) for the pairs, O(cells) for the gaps, a few per point plus
// ~30 per near-tangent spot. Not CGAL: the max rule's closest violating pair need not be a
// Delaunay edge, and G's maxima are not Voronoi vertices.
StatusOr<FieldVerifyReport> VerifyFieldDomain(std::span<const Vec2> points, const Rect& domain,
                                              const RadiusField& field,
                                              const FieldVerifyOptions& options = {});

// Judges a window of a larger point set, such as a plane world's rectangle with a halo of
// 2 r_max around it (plane/world_verifier.h): conflicts for every pair with an end in the
// half-open window, maximality at every unmasked spot of the closed window, both as above;
// points outside the window are context (they constrain and cover, and are not counted in
// points_checked or points_outside). A halo of 2 r_max is enough: no farther point can
// conflict with a point of the window or make G negative there. Errors and cost as above,
// naming "window".
StatusOr<FieldVerifyReport> VerifyFieldWindow(std::span<const Vec2> points, const Rect& window,
                                              const RadiusField& field,
                                              const FieldVerifyOptions& options = {});

}  // namespace scallop
