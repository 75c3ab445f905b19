// `scallop analyze` for radius-field point sets, where one d, and so rho and spectra in cycles
// per d, mean nothing globally: spacing judged against the local R (rho per band of R, nearest
// neighbours and pair distances over max(R(p), R(q))), and a picture of the points over the field.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "scallop/analysis/pair_spectrum.h"
#include "scallop/field/radius_field.h"
#include "scallop/geometry/rect.h"
#include "scallop/geometry/vec2.h"
#include "scallop/image/png_image.h"

namespace scallop::cli {

// One band of R: r_lo <= R < r_hi (the last band includes r_max).
struct FieldBand {
  double r_lo = 0, r_hi = 0;
  double area = 0;          // unmasked area of the window where R is in the band (grid estimate)
  int64_t points = 0;       // points whose R is in the band
  double sum_r2 = 0;        // sum of R(p)^2 over them
  int64_t nn_points = 0;    // those far enough inside the window to judge their neighbour
  double nn_ratio_sum = 0;  // sum of |p - q| / max(R(p), R(q)), q nearest by that ratio
  // Neighbour distances over R(p) from the band's points at least 6 R(p) inside the window:
  // the spectrum normalised by local R (PairRadialSpectrum, in cycles per R(p)).
  PairDistanceHistogram pairs;
  // rho normalised by local R: a set of spacing R(x) with normalised radius rho has local
  // density 2 rho^2 / (sqrt 3 R(x)^2), so sum over the band's points of R^2 ~ 2 rho^2 area /
  // sqrt 3 and rho = sqrt(sqrt 3 / 2 * sum_r2 / area). Uniform A3 gives 0.86
  // (docs/quality.md).
  double Rho() const;
  double NearestRatio() const { return nn_points > 0 ? nn_ratio_sum / nn_points : 0.0; }
};

struct FieldStatistics {
  std::vector<FieldBand> bands;  // geometric in R from r_min to r_max
  FieldBand all;                 // every band together
  int64_t conflicts = 0;         // pairs closer than max(R(p), R(q))
  double smallest_ratio = 0;  // smallest |p - q| / max(R(p), R(q)) over pairs (>= 1: no conflict)
  // Pair distances over max(R(p), R(q)) from the points far inside the window: neighbours
  // counted per bin of width kPairRatioStep from 0 to kPairRatioLimit, and those points. Per
  // point, 0 below 1 (the rule), a peak just above it, then growing with the ring's area: the
  // spatial twin of a spectrum, normalised by local R.
  std::vector<double> pair_ratio_counts;
  int64_t pair_ratio_points = 0;
  // pair_ratio_counts per point (0 when no point was far enough inside).
  std::vector<double> PairRatioPerPoint() const;
};

inline constexpr double kPairRatioStep = 0.05;
inline constexpr double kPairRatioLimit = 3.0;

// Adds one set's statistics to `total` (sums; bands made on first use). The band areas come
// from R sampled at the centres of a 256 x 256 grid over `window`, masked spots left out.
// Points "far inside" are at least 3 r_max from the window's edges; a point's spectrum pairs
// are counted when it is at least 6 R(p) inside. O(points * neighbours + grid), neighbours
// through grids of side r_max and sqrt(r_min r_max).
void AddFieldStatistics(std::span<const Vec2> points, const RadiusField& field, const Rect& window,
                        int bands, FieldStatistics& total);

// A band's spectrum normalised by local R: the radial power from 0.2 to 3 cycles per R(p)
// (below 0.2 the 6 R reach of the pairs resolves nothing), its mean below 0.5, and its peak. For a
// set of one spacing this is the ordinary radial spectrum in cycles per d (docs/quality.md, "Radius
// fields").
struct BandSpectrum {
  std::vector<double> frequency;
  std::vector<double> power;
  double low_power = 0;  // mean power at 0.2 <= f < 0.5
  double peak_frequency = 0;
  double peak_power = 0;
};
BandSpectrum SpectrumOf(const FieldBand& band);

// The points over the field: R in grey (light where R is large), masked pixels in dark red, each
// point a dot inside a ring of radius R/2. `size` pixels along the window's longer side.
Image8 RenderPointsOverField(std::span<const Vec2> points, const RadiusField& field,
                             const Rect& window, int size);

}  // namespace scallop::cli
