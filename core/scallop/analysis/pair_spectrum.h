// The radial power spectrum from pair distances: the Hankel transform of the pair correlation
// function. Unlike the periodogram it needs no square window and no one spacing for the whole
// set: each point's neighbours may be measured in its own unit (the local spacing R(p) of a
// radius field), the normalisation of Wei and Wang's differential domain analysis (SIGGRAPH
// 2011) for non-uniform sampling. For a set of one spacing d it estimates the same radially
// averaged power as the periodogram (radial_spectrum.h), in cycles per d.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace scallop {

// Neighbour distances in units of a spacing (d, or R(p) per point), binned. A point is
// counted only if every neighbour closer than `cutoff` spacings was offered (it lies at least
// that far inside the set's window); its neighbours go in counts.
struct PairDistanceHistogram {
  // Bins of this width from 0 to cutoff, in spacings. 0.005 keeps the phase error of a bin's
  // centre, pi f width, below 0.05 rad up to f = 3 cycles per spacing.
  static constexpr double kBinWidth = 0.005;
  // How far neighbours are counted: the pair correlation of a Poisson-disk set is within a
  // few per cent of 1 beyond 4 spacings; the last 1.5 spacings estimate the density.
  static constexpr double kCutoff = 6.0;

  std::vector<double> counts = std::vector<double>(static_cast<size_t>(kCutoff / kBinWidth), 0.0);
  int64_t points = 0;  // points whose neighbours were counted

  // One neighbour at `distance` spacings (ignored at or beyond kCutoff, or below 0).
  void AddNeighbour(double distance) {
    if (distance >= 0 && distance < kCutoff) counts[static_cast<size_t>(distance / kBinWidth)] += 1;
  }
  // Sums another histogram into this one.
  void Add(const PairDistanceHistogram& other);
};

// The radial power at each frequency f (cycles per spacing):
//   P(f) = 1 + sum_b taper(s_b) (c_b / N - n A_b) J0(2 pi f s_b),
// with c_b / N the neighbours per point in bin b (centre s_b, annulus area A_b) and n the
// density in points per spacing^2, estimated from the neighbours between 4.5 and 6 spacings
// (where the pair correlation is 1). The taper (1 up to 4 spacings, a half cosine to 0 at 6)
// damps the ringing of the cut, at the cost of smoothing the peak over about 1/6 cycle per
// spacing. For a stationary set, E[P(f)] is the radially averaged periodogram's; independent
// uniform points give 1 at every f > 0. Frequencies below about 1 / kCutoff are not resolved:
// there P(f) is dominated by the density estimate's error (a 1% error moves P(0) by about 1).
// Empty histogram: every value 1. O(bins * frequencies).
std::vector<double> PairRadialSpectrum(const PairDistanceHistogram& histogram,
                                       std::span<const double> frequencies);

// The density estimate the spectrum subtracts: neighbours per point per spacing^2 between
// 4.5 and 6 spacings (0 when no point was counted).
double PairHistogramDensity(const PairDistanceHistogram& histogram);

}  // namespace scallop
