// Wei's multi-class dart throwing (SIGGRAPH 2010, "Multi-class blue noise sampling", its
// hard-disk algorithm): every class is filled at once, each dart thrown for the class furthest
// below its target, and a dart may push out points of a smaller-spacing class. The joint scheme
// that layered sampling (one layer after another, layered_sampler.h) is compared against in
// docs/quality.md ("Layered worlds"). A baseline for analysis only: bounded, constant spacings,
// and, being dart throwing, not maximal.
#pragma once

#include <cstdint>
#include <vector>

#include "scallop/base/status.h"
#include "scallop/sampling/layered_sampler.h"

namespace scallop {

inline constexpr int64_t kMaxMultiClassTarget = 1'000'000'000;

struct MultiClassDartOptions {
  // The domain, each layer's constant spacing d and the matrix D, as SampleLayers reads them;
  // `order` and the layers' seeds are not read (every class is filled at once).
  LayeredSamplerOptions layers;
  // Each layer's target count N_c, in 1..kMaxMultiClassTarget. A dart is thrown for the class whose
  // count is the smallest fraction of its target (ties: the lower number).
  std::vector<int64_t> targets;
  // The run stops when every class has its target, after `failure_limit` rejected darts in a
  // row, or after `max_darts` darts in all (a dart that pushes points out is not rejected, so
  // only this bounds a run that keeps trading points).
  int64_t failure_limit = 100000;
  int64_t max_darts = 1'000'000'000;
  uint64_t seed = 0;
  // Wei's removal (below); false: plain multi-class dart throwing, every conflict rejects.
  bool removal = true;
};

// Checks what ValidateLayeredSamplerOptions checks, then INVALID_ARGUMENT for a field layer
// ("layers.layers[k].field"), targets not one per layer or out of range ("targets[k]"), and a
// failure_limit or max_darts that is not positive.
Status ValidateMultiClassDartOptions(const MultiClassDartOptions& options);

// Validates, then throws darts. Pure: the same options give the same bits. A dart for class c
// at p is kept when every point q of every class j keeps |p - q| >= D[c][j] (d_c for j = c, in
// doubles); otherwise, when every point it is too close to belongs to a class j with a smaller
// spacing (d_j < d_c) and at least c's fraction of its target, those points are removed and
// the dart kept (Wei's removal, which lets the large classes fill); otherwise it is rejected.
// Returns the points by layer number, each layer's in the order kept.
// Cost: O(darts * neighbours), each dart one grid query per class.
StatusOr<LayeredPoints> SampleMultiClassDarts(const MultiClassDartOptions& options);

}  // namespace scallop
