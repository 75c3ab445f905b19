// Point-set statistics for judging a sampler's output beyond the contract:
// the normalised radius (how dense a Poisson-disk set is) and the pair
// distance histogram with its radial distribution function g(r).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "scallop/base/status.h"
#include "scallop/geometry/domain.h"
#include "scallop/geometry/vec2.h"

namespace scallop {

// Lagae & Dutre 2008's normalised radius: d / d_max, where d_max =
// sqrt(2 / (sqrt(3) * N / area)) is the spacing of the hexagonal lattice with
// the same density, the densest packing. 1 for that lattice; maximal random
// sequential adsorption (exact dart throwing) gives about 0.777. O(1).
// Rejects (INVALID_ARGUMENT): point_count <= 0, area or d not finite and > 0.
StatusOr<double> NormalisedRadius(int64_t point_count, double area, double min_distance);

struct PairDistanceHistogram {
  double max_distance = 0.0;
  double bin_width = 0.0;  // bin k holds distances in [k, k + 1) * bin_width
  // Unordered pairs per bin (minimum-image distances on a torus).
  std::vector<int64_t> pair_counts;
  // g(r) per bin: pair_counts over the pairs expected in that bin if the same
  // number of points were independent and uniform in the domain. On a torus
  // that is N (N - 1) / 2 * annulus area / domain area; on a rectangle the
  // annulus is weighted by the rectangle's set covariance (W - |dx|)(H - |dy|),
  // so edge effects do not bias g. 0 where nothing is expected (N < 2).
  std::vector<double> radial_distribution;
};

// Histograms the distances of all pairs closer than max_distance, with a
// uniform grid of cells at least max_distance wide: O(N + pairs within reach
// of a cell's neighbours), about 9 * density * max_distance^2 pairs per point.
// Rejects (INVALID_ARGUMENT): a non-finite or empty rectangle; max_distance
// not finite and > 0, or above min(width, height) (half of it on a torus, so
// that a pair has one image within reach); bin_count outside [1, 1e7];
// points outside the half-open rectangle or non-finite.
StatusOr<PairDistanceHistogram> HistogramPairDistances(std::span<const Vec2> points,
                                                       const Domain& domain, double max_distance,
                                                       int bin_count);

}  // namespace scallop
