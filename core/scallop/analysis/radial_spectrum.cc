// Radial mean power and anisotropy by binning a periodogram into unit-width
// annuli (see radial_spectrum.h).
#include "scallop/analysis/radial_spectrum.h"

#include <cmath>
#include <limits>

namespace scallop {

StatusOr<RadialSpectrum> ComputeRadialSpectrum(const Periodogram& periodogram) {
  const int k_max = periodogram.max_frequency;
  if (k_max < 1 ||
      periodogram.power.size() != static_cast<size_t>(periodogram.side()) * periodogram.side()) {
    return InvalidArgument("periodogram: power must hold (2 max_frequency + 1)^2 values");
  }
  // Two passes (mean, then squared deviations) rather than sums of squares,
  // which cancel badly when an annulus is nearly uniform.
  std::vector<double> sum(k_max + 1, 0.0), squares(k_max + 1, 0.0);
  std::vector<int64_t> count(k_max + 1, 0);
  auto annulus = [](int kx, int ky) {
    return static_cast<int>(std::floor(std::sqrt(double(kx) * kx + double(ky) * ky) + 0.5));
  };
  for (int ky = -k_max; ky <= k_max; ++ky) {
    for (int kx = -k_max; kx <= k_max; ++kx) {
      const int r = annulus(kx, ky);
      if (r < 1 || r > k_max) continue;
      sum[r] += periodogram.At(kx, ky);
      ++count[r];
    }
  }
  RadialSpectrum result;
  for (int r = 1; r <= k_max; ++r) {
    result.frequency.push_back(r);
    result.count.push_back(count[r]);
    result.mean_power.push_back(sum[r] / static_cast<double>(count[r]));
  }
  for (int ky = -k_max; ky <= k_max; ++ky) {
    for (int kx = -k_max; kx <= k_max; ++kx) {
      const int r = annulus(kx, ky);
      if (r < 1 || r > k_max) continue;
      const double deviation = periodogram.At(kx, ky) - result.mean_power[r - 1];
      squares[r] += deviation * deviation;
    }
  }
  for (int r = 1; r <= k_max; ++r) {
    const double variance = squares[r] / static_cast<double>(count[r] - 1);
    const double mean = result.mean_power[r - 1];
    result.anisotropy_db.push_back(variance > 0 ? 10.0 * std::log10(variance / (mean * mean))
                                                : -std::numeric_limits<double>::infinity());
  }
  return result;
}

size_t PeakAnnulus(const RadialSpectrum& spectrum) {
  size_t peak = 0;
  for (size_t i = 0; i < spectrum.mean_power.size(); ++i) {
    if (spectrum.mean_power[i] > spectrum.mean_power[peak]) peak = i;
  }
  return peak;
}

double LowFrequencyPower(const RadialSpectrum& spectrum) {
  const double half_peak = spectrum.frequency[PeakAnnulus(spectrum)] / 2;
  double sum = 0;
  int count = 0;
  for (size_t i = 0; i < spectrum.frequency.size() && spectrum.frequency[i] < half_peak;
       ++i, ++count) {
    sum += spectrum.mean_power[i];
  }
  return count > 0 ? sum / count : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace scallop
