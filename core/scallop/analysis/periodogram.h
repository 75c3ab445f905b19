// The periodogram of a point set in a square window, |sum_j exp(-2 pi i k.x_j / L)|^2 / N
// at integer frequencies k, computed by FFTW from a fine grid, and its average
// over many sets (McCool & Fiume 1992; Lagae & Dutre 2008).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "scallop/base/status.h"
#include "scallop/geometry/rect.h"
#include "scallop/geometry/vec2.h"

namespace scallop {

// Largest max_frequency accepted: the FFT grid is then 2048^2 (about 70 MB).
inline constexpr int kMaxPeriodogramFrequency = 256;

// Power at the integer frequencies k = (kx, ky), |kx|, |ky| <= max_frequency,
// in cycles per window side L (k / L in cycles per unit length). Normalised by
// the point count, so independent uniform points have expected power 1 at
// every k != 0, whatever N; the DC term k = 0 holds N (mean of N over sets).
struct Periodogram {
  int max_frequency = 0;
  int set_count = 0;        // sets averaged (1 for one set)
  int64_t point_count = 0;  // points over all sets
  // (2 max_frequency + 1)^2 values; row r holds ky = r - max_frequency, column
  // c holds kx = c - max_frequency.
  std::vector<double> power;

  int side() const { return 2 * max_frequency + 1; }
  // REQUIRES: |kx|, |ky| <= max_frequency.
  double At(int kx, int ky) const {
    return power[static_cast<size_t>(ky + max_frequency) * side() + (kx + max_frequency)];
  }
};

// The FFT grid side for max_frequency K: the smallest power of two >= 8 K
// (and >= 64).
int PeriodogramGridSize(int max_frequency);

// The periodogram of `points` in the square `window` of side L. Integer
// frequencies make the window's own transform vanish at every k != 0, so a
// window cut from a larger set shows no leakage from its edges in the mean.
//
// Method: each point is spread on a periodic M x M grid (M =
// PeriodogramGridSize) by the cubic B-spline, the grid is transformed by FFTW
// (r2c, FFTW_ESTIMATE, so the plan does not depend on timing), and each
// coefficient is divided by the spline's transform sinc^4(pi kx / M)
// sinc^4(pi ky / M). What remains of the spreading is aliasing: the sum over
// every point of exp(-2 pi i k.x / L) is exact up to an error of at most
// N ((1 + a(kx / M)) (1 + a(ky / M)) - 1), where a(u) = u^4 sum_{m != 0} (u + m)^-4
// (a(1/8) = 6.1e-4), i.e. about 1e-3 N at the highest frequency and 1e-7 N
// at a tenth of it. Versus the direct sum, O(N K^2), this costs
// O(16 N + M^2 log M): 90 ms for K = 100 or 128 (M = 1024), 6 ms for K = 20,
// 0.4 s for K = 256, with 2000 points (-O3, a shared 2-core machine under
// load); the grid, not N, dominates.
// Not bit-identical across machines (FFTW picks SIMD kernels per CPU); it
// judges points and never makes them. Thread-safe: FFTW planning is serialised.
// Rejects (INVALID_ARGUMENT): a window that is not finite or not square (sides
// differing by more than 1e-9 of the side), an empty point set, a point that
// is not finite or lies outside the half-open window, max_frequency outside
// [1, kMaxPeriodogramFrequency].
StatusOr<Periodogram> ComputePeriodogram(std::span<const Vec2> points, const Rect& window,
                                         int max_frequency);

// The mean of periodograms with the same max_frequency, each weighted as one
// set (Lagae & Dutre average sets, not points). O(sets (2K+1)^2).
class PeriodogramAverage {
 public:
  // Adds one periodogram (itself possibly an average of several sets, which
  // then count as that many). Rejects (INVALID_ARGUMENT) a max_frequency
  // different from the first one's, or an empty periodogram.
  Status Add(const Periodogram& periodogram);

  // The average so far. INVALID_ARGUMENT when nothing was added.
  StatusOr<Periodogram> Mean() const;

 private:
  Periodogram sum_;  // power summed, weighted by set_count
};

}  // namespace scallop
