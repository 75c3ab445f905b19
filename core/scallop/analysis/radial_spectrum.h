// Radial mean power and anisotropy of a periodogram, the one-dimensional
// summaries of McCool & Fiume 1992 and Lagae & Dutre 2008, after Ulichney.
#pragma once

#include <cstdint>
#include <vector>

#include "scallop/analysis/periodogram.h"

namespace scallop {

// One entry per annulus r = 1..max_frequency: the integer frequencies k with
// r - 1/2 <= |k| < r + 1/2 (only those inside the periodogram's square, so
// every annulus is whole). The DC term is in no annulus.
struct RadialSpectrum {
  std::vector<double> frequency;   // r, in cycles per window side
  std::vector<int64_t> count;      // frequencies in the annulus (k and -k both count)
  std::vector<double> mean_power;  // P_r: mean power over the annulus
  // 10 log10(s^2 / P_r^2), s^2 the unbiased sample variance over the annulus.
  // An average of S periodograms of independent uniform points has power
  // values of mean 1 and variance 1 / S, hence anisotropy -10 log10 S dB: the
  // floor against which Lagae & Dutre read a method's anisotropy. -infinity
  // when the annulus is perfectly uniform.
  std::vector<double> anisotropy_db;
};

// Radial mean power and anisotropy of `periodogram`. O((2K + 1)^2).
// Rejects (INVALID_ARGUMENT) a periodogram whose power array does not match
// its max_frequency.
StatusOr<RadialSpectrum> ComputeRadialSpectrum(const Periodogram& periodogram);

// The annulus of largest mean power (the first of equals). REQUIRES: at least one annulus.
size_t PeakAnnulus(const RadialSpectrum& spectrum);

// The mean power of the annuli below half the peak's frequency: the depth of
// the low-energy disk (small for good blue noise, 1 for white). NaN when no
// annulus lies below it. REQUIRES: at least one annulus.
double LowFrequencyPower(const RadialSpectrum& spectrum);

}  // namespace scallop
