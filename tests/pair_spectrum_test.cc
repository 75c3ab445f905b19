// PairRadialSpectrum against what it must equal: for A3 sets of one spacing d, the radially
// averaged periodogram (computed by FFT on the window, a different method) in bands of
// frequency; for independent uniform points, 1; and the same spectrum in cycles per spacing
// for a set scaled with its spacing. Neighbours are found by looking at every pair.
#include "scallop/analysis/pair_spectrum.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <vector>

#include "scallop/analysis/periodogram.h"
#include "scallop/analysis/radial_spectrum.h"
#include "scallop/random/rng.h"
#include "scallop/sampling/sampler.h"

namespace scallop {
namespace {

// Every pair's distance over `spacing`, for the points at least kCutoff spacings inside: the
// points sorted by x, each against those within kCutoff spacings of it in x (every pair
// closer than that is among them).
PairDistanceHistogram HistogramOf(std::vector<Vec2> points, const Rect& window, double spacing) {
  std::sort(points.begin(), points.end(), [](Vec2 a, Vec2 b) { return a.x < b.x; });
  PairDistanceHistogram histogram;
  const double margin = PairDistanceHistogram::kCutoff * spacing;
  for (size_t a = 0; a < points.size(); ++a) {
    const Vec2 p = points[a];
    if (p.x - window.x0 < margin || window.x1 - p.x < margin || p.y - window.y0 < margin ||
        window.y1 - p.y < margin) {
      continue;
    }
    ++histogram.points;
    const auto first = std::lower_bound(points.begin(), points.end(), p.x - margin,
                                        [](Vec2 q, double x) { return q.x < x; });
    for (auto q = first; q != points.end() && q->x <= p.x + margin; ++q) {
      if (q - points.begin() != static_cast<std::ptrdiff_t>(a)) {
        histogram.AddNeighbour(std::hypot(q->x - p.x, q->y - p.y) / spacing);
      }
    }
  }
  return histogram;
}

std::vector<double> Frequencies(double step, double last) {
  std::vector<double> f;
  for (double v = step; v <= last + 1e-9; v += step) f.push_back(v);
  return f;
}

// Mean of `values` where lo <= f < hi.
double BandMean(const std::vector<double>& f, const std::vector<double>& values, double lo,
                double hi) {
  double sum = 0;
  int n = 0;
  for (size_t k = 0; k < f.size(); ++k) {
    if (f[k] >= lo && f[k] < hi) sum += values[k], ++n;
  }
  return n > 0 ? sum / n : NAN;
}

// Four A3 sets of 64 d squares: the pair spectrum and the averaged periodogram's radial mean
// agree band by band, from the low frequencies through the peak to the flat tail.
TEST(PairSpectrumTest, MatchesThePeriodogramOnA3Sets) {
  constexpr double kSide = 64.0;
  constexpr int kMaxFrequency = 192;  // 3 cycles per d
  const Rect window{0, 0, kSide, kSide};
  PairDistanceHistogram pairs;
  PeriodogramAverage average;
  for (uint64_t seed = 1; seed <= 4; ++seed) {
    SamplerOptions options;
    options.domain = Domain{window, false};
    options.seed = seed;
    const std::vector<Vec2> points = *Sample(options);
    pairs.Add(HistogramOf(points, window, 1.0));
    ASSERT_TRUE(average.Add(*ComputePeriodogram(points, window, kMaxFrequency)).ok());
  }
  const RadialSpectrum radial = *ComputeRadialSpectrum(*average.Mean());
  std::vector<double> f_periodogram;
  for (const double r : radial.frequency) f_periodogram.push_back(r / kSide);
  const std::vector<double> f = Frequencies(0.02, 3.0);
  const std::vector<double> power = PairRadialSpectrum(pairs, f);
  // Bands: below the peak, its rise, the peak, the ripple after it, the tail.
  const double bands[][2] = {{0.1, 0.5}, {0.5, 0.8}, {0.8, 1.2}, {1.2, 2.0}, {2.0, 3.0}};
  for (const auto& band : bands) {
    const double by_pairs = BandMean(f, power, band[0], band[1]);
    const double by_fft = BandMean(f_periodogram, radial.mean_power, band[0], band[1]);
    std::printf("f in [%.1f, %.1f) / d: pairs %.3f, periodogram %.3f\n", band[0], band[1], by_pairs,
                by_fft);
    // The periodogram's band means carry about 3% noise (a few hundred frequencies of 4 sets
    // each); the taper smooths the peak by about a sixth of a cycle per d.
    EXPECT_NEAR(by_pairs, by_fft, 0.04 + 0.03 * by_fft) << band[0];
  }
  // Blue noise: little power at low frequencies, a peak above 1 near 1 / d.
  EXPECT_LT(BandMean(f, power, 0.1, 0.5), 0.3);
  EXPECT_GT(BandMean(f, power, 0.8, 1.2), 1.1);
  // The density estimate is the set's: about 0.85 points per d^2 for A3.
  EXPECT_NEAR(PairHistogramDensity(pairs), 0.85, 0.05);
}

// Independent uniform points: flat at 1.
TEST(PairSpectrumTest, UniformPointsAreWhite) {
  Rng rng(11);
  const Rect window{0, 0, 60, 60};
  PairDistanceHistogram pairs;
  for (int set = 0; set < 3; ++set) {
    std::vector<Vec2> points;
    for (int k = 0; k < 3600; ++k) {
      points.push_back({rng.Uniform(window.x0, window.x1), rng.Uniform(window.y0, window.y1)});
    }
    pairs.Add(HistogramOf(points, window, 1.0));
  }
  const std::vector<double> f = Frequencies(0.05, 3.0);
  const std::vector<double> power = PairRadialSpectrum(pairs, f);
  for (size_t k = 0; k < f.size(); ++k) {
    if (f[k] >= 0.3) {
      EXPECT_NEAR(power[k], 1.0, 0.15) << "f " << f[k];
    }
  }
}

// Distances in units of the spacing: a set and its copy scaled by 2.5, measured in 1 and 2.5,
// have the same spectrum, and an empty histogram is white.
TEST(PairSpectrumTest, UnitsAreSpacingsAndEmptyIsWhite) {
  SamplerOptions options;
  options.domain = Domain{{0, 0, 40, 40}, false};
  options.seed = 3;
  const std::vector<Vec2> points = *Sample(options);
  std::vector<Vec2> scaled;
  for (const Vec2& p : points) scaled.push_back({2.5 * p.x, 2.5 * p.y});
  const std::vector<double> f = Frequencies(0.1, 2.0);
  const std::vector<double> a = PairRadialSpectrum(HistogramOf(points, {0, 0, 40, 40}, 1.0), f);
  const std::vector<double> b = PairRadialSpectrum(HistogramOf(scaled, {0, 0, 100, 100}, 2.5), f);
  for (size_t k = 0; k < f.size(); ++k) EXPECT_NEAR(a[k], b[k], 1e-9) << f[k];
  for (const double v : PairRadialSpectrum(PairDistanceHistogram{}, f)) EXPECT_EQ(v, 1.0);
}

}  // namespace
}  // namespace scallop
