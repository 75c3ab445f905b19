// The verifier: judges a point set against the two geometric contract items,
// spacing (every pair at least d apart in double precision) and maximality (no
// spot of the judged area farther than d from every point), with CGAL's Delaunay.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <span>

#include "scallop/base/status.h"
#include "scallop/geometry/domain.h"
#include "scallop/geometry/rect.h"
#include "scallop/geometry/vec2.h"
#include "scallop/verify/field_verifier.h"
#include "scallop/verify/layer_verifier.h"

namespace scallop {

struct VerifyOptions {
  // maximal_ok is largest_empty_circle < d * (1 + max_tolerance). Samplers do
  // not keep points exactly d apart: they place them at SpacingFor(d, M) = d +
  // max(d * 2^-32, 8 ulp(M)) (sampling/spacing.h) so that rounding never breaks
  // the spacing contract, which leaves the set maximal only for that slightly
  // larger radius. 1e-9 covers d * 2^-32 (2.3e-10 d) with room for the rounding
  // of the circumcentres, and 8 ulp(M) up to |coordinates| of about 5e5 d;
  // pass (SpacingFor(d, M) - d) / d * 2 or so when judging worlds farther out.
  double max_tolerance = 1e-9;
  // When > 0, points lie in square regions of this side aligned at its
  // multiples (region of p = (floor(p.x / S), floor(p.y / S))) and the report
  // also counts the judged pairs whose endpoints lie in different regions.
  double seam_spacing = 0.0;
  // When set, polled every 16,384 insertions and scan steps: once it returns
  // true the verifier stops and returns CANCELLED (its caller has gone).
  std::function<bool()> stop;
};

// What the verifier found. Pairs are Delaunay edges: the closest pair of any
// set is one, and so is the closest violating pair (a pair that is not a
// Delaunay edge has a point in its diametral disk, hence a pair at most
// 1/sqrt(2) as long), so spacing_violations == 0 exactly when no pair violates.
struct VerifyReport {
  int64_t points_checked = 0;  // points inside the judged area
  int64_t points_outside = 0;  // VerifyDomain only: points outside the domain's rectangle
  int64_t pairs_checked = 0;   // Delaunay edges judged (on a torus each periodic edge once)
  // Closest judged pair, by dx^2 + dy^2 in double precision. closest_b is the
  // image (on a torus, the translate) of the second point nearest closest_a;
  // the indices are positions in the input span, -1 when no pair was judged.
  double min_distance = std::numeric_limits<double>::infinity();
  Vec2 closest_a, closest_b;
  int64_t closest_index_a = -1, closest_index_b = -1;
  // Judged Delaunay edges (and exactly coincident points) with dx^2 + dy^2 < d^2.
  int64_t spacing_violations = 0;
  // Radius of the largest circle centred in the judged area that has no point
  // inside it, and its centre (infinity when there are no points). Exact up to
  // rounding while below the coverage (2 d around a window, the replicated band
  // on a torus); a value at or above it is an upper bound, and then the true
  // radius is at least the coverage too, so maximal_ok is right either way.
  double largest_empty_circle = 0.0;
  Vec2 largest_empty_centre;
  // Seam statistics, filled when VerifyOptions::seam_spacing > 0.
  int64_t pairs_across_seams = 0;
  double min_distance_across_seams = std::numeric_limits<double>::infinity();
  int64_t spacing_violations_across_seams = 0;

  bool spacing_ok = false;  // spacing_violations == 0
  bool maximal_ok = false;  // largest_empty_circle < d * (1 + max_tolerance)
  // A radius-field world's window (plane/world_verifier.h): the field verifier's report, whose
  // verdicts spacing_ok and maximal_ok repeat (conflicts under the max rule, the certified
  // bound of G); spacing_violations is its conflict count, min_distance and the closest pair
  // its pair of least |p - q| / max(R(p), R(q)), largest_empty_centre its largest gap's spot.
  // largest_empty_circle and the seam statistics stay unset: they are the constant rule's.
  std::optional<FieldVerifyReport> field;
  // A layered world's window: the layered verifier's report (layer_verifier.h), whose verdicts
  // spacing_ok (no conflict within a layer or across layers) and maximal_ok (every layer
  // maximal given the others) repeat; spacing_violations counts both kinds of conflict.
  std::optional<LayerVerifyReport> layered;
  bool passed() const {
    return spacing_ok && maximal_ok && points_outside == 0 && (!field || field->passed()) &&
           (!layered || layered->passed());
  }
};

// Judges a bounded sampler's output.
// On a rectangle the judged area is the closed rectangle (the half-open one
// plus its boundary, where F1 also peaks: at corners and where Voronoi edges
// cross a side); every pair is judged; points outside the half-open rectangle
// are counted in points_outside and fail the report.
// On a torus distances are minimum-image: points within 2 d of an edge are
// replicated shifted by +-width / +-height (the band doubles while a larger
// empty circle is found, up to every image), and each pair is judged once.
// The pair's squared distance is the smaller of p - (q + shift) and
// q - (p - shift), the expression a sampler evaluates for either order.
// Rejects (INVALID_ARGUMENT): non-finite or empty rectangle, d <= 0 or
// non-finite, non-finite points, negative or non-finite options. CANCELLED
// when options.stop asked it to stop.
// Cost: O(N log N) (a Hilbert sort, then O(1) expected per insertion): 1.0 to
// 1.4 s of one core per million points at -O3 (shared 2-core machine; test
// DelaunayVerifierTest.MillionPoints), three quarters of it the triangulation;
// about 250 bytes per point at the peak. A torus adds the band (a few
// per cent), and each doubling of the band, which only a set failing
// maximality by more than 2 d triggers, repeats the whole scan.
StatusOr<VerifyReport> VerifyDomain(std::span<const Vec2> points, const Domain& domain,
                                    double min_distance, const VerifyOptions& options = {});

// Judges a window of an infinite point set. REQUIRES (not checkable): `points`
// hold every point of the set within the window grown by 2 d on every side;
// points farther out may be present and are harmless.
// Judges the pairs with at least one end inside the half-open window and the
// empty circles centred in the closed window. Same rejections and cost as
// VerifyDomain; points_outside is always 0.
StatusOr<VerifyReport> VerifyWindow(std::span<const Vec2> points, const Rect& window,
                                    double min_distance, const VerifyOptions& options = {});

}  // namespace scallop
