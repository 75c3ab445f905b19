// PairRadialSpectrum: neighbours per point per bin, less the uniform expectation, transformed
// with J0 (the radial Fourier transform in the plane).
#include "scallop/analysis/pair_spectrum.h"

#include <cmath>
#include <numbers>

namespace scallop {
namespace {

constexpr double kTaperStart = 4.0;   // spacings: 1 below
constexpr double kDensityFrom = 4.5;  // spacings: the density's annulus starts here

double Taper(double s) {
  if (s <= kTaperStart) return 1.0;
  const double t = (s - kTaperStart) / (PairDistanceHistogram::kCutoff - kTaperStart);
  return 0.5 * (1.0 + std::cos(std::numbers::pi * t));
}

}  // namespace

void PairDistanceHistogram::Add(const PairDistanceHistogram& other) {
  for (size_t b = 0; b < counts.size(); ++b) counts[b] += other.counts[b];
  points += other.points;
}

double PairHistogramDensity(const PairDistanceHistogram& histogram) {
  if (histogram.points == 0) return 0.0;
  const auto first = static_cast<size_t>(kDensityFrom / PairDistanceHistogram::kBinWidth);
  double neighbours = 0;
  for (size_t b = first; b < histogram.counts.size(); ++b) neighbours += histogram.counts[b];
  const double inner = static_cast<double>(first) * PairDistanceHistogram::kBinWidth;
  const double outer = PairDistanceHistogram::kCutoff;
  const double area = std::numbers::pi * (outer * outer - inner * inner);
  return neighbours / static_cast<double>(histogram.points) / area;
}

std::vector<double> PairRadialSpectrum(const PairDistanceHistogram& histogram,
                                       std::span<const double> frequencies) {
  std::vector<double> power(frequencies.size(), 1.0);
  if (histogram.points == 0) return power;
  const double density = PairHistogramDensity(histogram);
  const double w = PairDistanceHistogram::kBinWidth;
  // Each bin's excess of neighbours per point over the uniform expectation, tapered.
  std::vector<double> excess(histogram.counts.size());
  std::vector<double> centre(histogram.counts.size());
  for (size_t b = 0; b < excess.size(); ++b) {
    const double inner = static_cast<double>(b) * w, outer = inner + w;
    centre[b] = inner + 0.5 * w;
    const double expected = density * std::numbers::pi * (outer * outer - inner * inner);
    excess[b] =
        Taper(centre[b]) * (histogram.counts[b] / static_cast<double>(histogram.points) - expected);
  }
  for (size_t k = 0; k < frequencies.size(); ++k) {
    const double omega = 2 * std::numbers::pi * frequencies[k];
    double sum = 0;
    for (size_t b = 0; b < excess.size(); ++b) {
      if (excess[b] != 0) sum += excess[b] * std::cyl_bessel_j(0.0, omega * centre[b]);
    }
    power[k] += sum;
  }
  return power;
}

}  // namespace scallop
