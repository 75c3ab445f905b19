// The verifier for layered worlds (issue 19): every pair of points judged under the exclusion
// matrix D (a pair of one layer by the layer's own rule, a pair of layers a != b by
// |p - q| >= D[a][b]), and each layer's maximality given all the others: every spot of the
// window that no other layer's point excludes (|x - q| < D) and no mask covers has a point of
// the layer within its spacing. docs/design.md, "Layers".
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "scallop/base/status.h"
#include "scallop/field/radius_field.h"
#include "scallop/geometry/rect.h"
#include "scallop/geometry/vec2.h"
#include "scallop/verify/field_verifier.h"

namespace scallop {

struct LayerVerifyReport {
  // Layer k's own report: its pairs by its rule and its gaps, with every other layer's points as
  // exclusion disks of radius D[j][k] (FieldVerifyOptions::exclusions).
  std::vector<FieldVerifyReport> layers;
  // Pairs of points of different layers a, b within D[a][b] of each other with an end in the
  // window, each once; those with dx^2 + dy^2 < D[a][b]^2 in doubles (the sampler's expression).
  int64_t cross_pairs_checked = 0;
  int64_t cross_conflicts = 0;
  // The smallest |p - q| / D[a][b] over those pairs, and its pair (input indices; -1: none).
  double min_cross_ratio = std::numeric_limits<double>::infinity();
  int64_t closest_cross_a = -1, closest_cross_b = -1;

  bool passed() const {
    if (cross_conflicts != 0) return false;
    for (const FieldVerifyReport& layer : layers) {
      if (!layer.passed()) return false;
    }
    return true;
  }
};

// Judges a window of a layered point set: points[k] belongs to layer layer_of[k]; layer k's
// spacing rule is fields[k] (RadiusField::Constant(d) for a constant layer, whose rule max(d, d)
// is d's); matrix is D, n x n row-major with n = fields.size(), symmetric, diagonal unused.
// REQUIRES (not checkable): the points hold every point within the window grown by
// max(2 largest r_max, largest D). Rejects (INVALID_ARGUMENT): sizes that disagree
// ("layers"), a layer number >= n ("layers"), a matrix entry negative or not finite ("matrix"),
// and what VerifyFieldWindow rejects. `options.exclusions` must be empty (the others' points
// are the exclusions).
// Cost: each layer's VerifyFieldWindow with the other layers' points as disks, and the cross
// pairs through a grid of side the largest D: O(N) for bounded D and spacings.
StatusOr<LayerVerifyReport> VerifyLayeredWindow(std::span<const Vec2> points,
                                                std::span<const uint8_t> layer_of,
                                                const Rect& window,
                                                std::span<const RadiusField> fields,
                                                std::span<const double> matrix,
                                                const FieldVerifyOptions& options = {});

}  // namespace scallop
