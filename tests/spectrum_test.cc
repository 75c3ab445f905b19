// Tests of the periodogram and its radial summaries: the FFT periodogram
// against the direct sum on random sets, the known spectra of a lattice and
// of white noise, and each check shown to catch a planted fault.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "scallop/analysis/periodogram.h"
#include "scallop/analysis/radial_spectrum.h"
#include "scallop/random/rng.h"

namespace scallop {
namespace {

std::vector<Vec2> UniformPoints(uint64_t seed, int count, const Rect& window) {
  Rng rng(HashWords({seed, 0x5eed}));
  std::vector<Vec2> points;
  for (int i = 0; i < count; ++i) {
    points.push_back({rng.Uniform(window.x0, window.x1), rng.Uniform(window.y0, window.y1)});
  }
  return points;
}

// The obviously right twin: sum_j exp(-2 pi i k.(x_j - o) / L), in long double.
std::complex<long double> DirectSum(const std::vector<Vec2>& points, const Rect& window, int kx,
                                    int ky) {
  std::complex<long double> sum = 0;
  const long double side = window.Width();
  for (const Vec2& p : points) {
    const long double phase = -2 * std::numbers::pi_v<long double> *
                              (kx * (p.x - window.x0) + ky * (p.y - window.y0)) / side;
    sum += std::polar(1.0L, phase);
  }
  return sum;
}

// a(u) = u^4 sum_{m != 0} (u + m)^-4, the cubic spline's relative alias weight
// on one axis (periodogram.h), summed far enough that the tail is < 1e-12.
double AliasWeight(double u) {
  double sum = 0;
  for (int m = 1; m <= 20000; ++m) sum += std::pow(u + m, -4) + std::pow(u - m, -4);
  return std::pow(u, 4) * sum;
}

// Worst excess of | |F_fft| - |F_direct| | over the documented bound
// N ((1 + a_x)(1 + a_y) - 1) + 1e-9 N (rounding), over every frequency: < 0
// when the periodogram keeps its promise.
double WorstExcessOverBound(const std::vector<Vec2>& reference, const Periodogram& periodogram,
                            const Rect& window) {
  const int k_max = periodogram.max_frequency;
  const int m = PeriodogramGridSize(k_max);
  const double n = static_cast<double>(periodogram.point_count);
  std::vector<double> alias;  // alias[k + K] = a(k / M)
  for (int k = -k_max; k <= k_max; ++k) alias.push_back(AliasWeight(double(k) / m));
  double worst = -INFINITY;
  for (int ky = -k_max; ky <= k_max; ++ky) {
    for (int kx = -k_max; kx <= k_max; ++kx) {
      const double direct = static_cast<double>(std::abs(DirectSum(reference, window, kx, ky)));
      const double fft = std::sqrt(periodogram.At(kx, ky) * n);
      const double bound = n * ((1 + alias[kx + k_max]) * (1 + alias[ky + k_max]) - 1) + 1e-9 * n;
      worst = std::max(worst, std::abs(fft - direct) - bound);
    }
  }
  return worst;
}

TEST(PeriodogramTest, AliasWeightMatchesTheDocumentedFigure) {
  EXPECT_NEAR(AliasWeight(0.125), 6.1e-4, 0.05e-4);
}

TEST(PeriodogramTest, MatchesDirectSumOnRandomSets) {
  for (uint64_t seed = 1; seed <= 12; ++seed) {
    Rng rng(seed);
    const int count = 1 + static_cast<int>(rng.Below(150));
    const int k_max = 2 + static_cast<int>(rng.Below(30));
    const double x0 = rng.Uniform(-1e3, 1e3), y0 = rng.Uniform(-1e3, 1e3);
    const double side = rng.Uniform(0.5, 50);
    const Rect window{x0, y0, x0 + side, y0 + side};
    std::vector<Vec2> points = UniformPoints(seed, count, window);
    points[0] = {window.x0, window.y0};  // a point on the closed edges, which the grid wraps
    if (count > 1) points[1] = {std::nextafter(window.x1, x0), std::nextafter(window.y1, y0)};
    auto periodogram = ComputePeriodogram(points, window, k_max);
    ASSERT_TRUE(periodogram.ok()) << "seed " << seed << ": " << periodogram.status().message();
    EXPECT_NEAR(periodogram->At(0, 0), count, 1e-9 * count) << "seed " << seed;
    EXPECT_LT(WorstExcessOverBound(points, *periodogram, window), 0) << "seed " << seed;

    // Planted fault: the reference set with one point moved by L / 1000.
    if (count < 2) continue;
    std::vector<Vec2> moved = points;
    moved[count / 2].x = std::min(moved[count / 2].x + side / 1000, std::nextafter(window.x1, x0));
    moved[count / 2].y = std::max(moved[count / 2].y - side / 1000, window.y0);
    EXPECT_GT(WorstExcessOverBound(moved, *periodogram, window), 0) << "seed " << seed;
  }
}

// Lattice offsets to test: centred in the cells, and at their corners.
class LatticeTest : public testing::TestWithParam<double> {};

// An n x n lattice of spacing L / n sums to N at frequencies that are
// multiples of n on both axes and to 0 at every other integer frequency.
TEST_P(LatticeTest, HasPeaksOnlyAtMultiplesOfTheLatticeFrequency) {
  const int n = 10, k_max = 40;
  const Rect window{-3, 2, 7, 12};
  std::vector<Vec2> lattice;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) lattice.push_back({-3 + (i + GetParam()), 2 + (j + GetParam())});
  }
  auto worst_deviation = [&](const std::vector<Vec2>& points) {
    auto periodogram = ComputePeriodogram(points, window, k_max);
    EXPECT_TRUE(periodogram.ok());
    double worst = 0;
    for (int ky = -k_max; ky <= k_max; ++ky) {
      for (int kx = -k_max; kx <= k_max; ++kx) {
        const double want = (kx % n == 0 && ky % n == 0) ? n * n : 0.0;
        worst = std::max(worst, std::abs(periodogram->At(kx, ky) - want));
      }
    }
    return worst;
  };
  // Amplitude error <= 1.7e-4 N at K / M = 40 / 512 (both axes), so power
  // error <= 2 * 1.7e-4 N + (1.7e-4)^2 N = 0.035 at a peak, 3e-6 elsewhere.
  EXPECT_LT(worst_deviation(lattice), 0.04);
  // Planted fault: the lattice jittered by up to L / 500 (inwards, so the
  // points stay in the window) no longer has clean zeros.
  std::vector<Vec2> jittered = lattice;
  Rng rng(7);
  for (Vec2& p : jittered) p = p + Vec2{rng.Uniform(0, 0.02), rng.Uniform(0, 0.02)};
  EXPECT_GT(worst_deviation(jittered), 0.04);
}

INSTANTIATE_TEST_SUITE_P(Offsets, LatticeTest, testing::Values(0.5, 0.0));

// The average of `sets` periodograms of point sets made by `make(seed)`.
template <typename MakePoints>
Periodogram AveragePeriodogram(int sets, int k_max, const Rect& window, MakePoints make) {
  PeriodogramAverage average;
  for (int s = 0; s < sets; ++s) {
    auto periodogram = ComputePeriodogram(make(static_cast<uint64_t>(s)), window, k_max);
    EXPECT_TRUE(periodogram.ok()) << periodogram.status().message();
    EXPECT_TRUE(average.Add(*periodogram).ok());
  }
  auto mean = average.Mean();
  EXPECT_TRUE(mean.ok());
  return *mean;
}

constexpr int kWhiteSets = 16, kWhiteFrequency = 32, kWhitePoints = 400;
const Rect kUnitWindow{0, 0, 1, 1};

// Largest |P_r - 1| over annuli in standard errors: an annulus holds count
// values, half of them independent (P(-k) = P(k)), each of variance 1 / sets.
double WorstFlatnessZ(const RadialSpectrum& radial, int sets) {
  double worst = 0;
  for (size_t r = 0; r < radial.frequency.size(); ++r) {
    const double error = std::sqrt(2.0 / (static_cast<double>(radial.count[r]) * sets));
    worst = std::max(worst, std::abs(radial.mean_power[r] - 1) / error);
  }
  return worst;
}

// Mean of the linear anisotropy over annuli 8..K, where annuli hold 50+ values.
double MeanAnisotropy(const RadialSpectrum& radial) {
  double sum = 0;
  int annuli = 0;
  for (size_t r = 7; r < radial.frequency.size(); ++r, ++annuli) {
    sum += std::pow(10.0, radial.anisotropy_db[r] / 10);
  }
  return sum / annuli;
}

TEST(RadialSpectrumTest, WhiteNoiseIsFlatWithAnisotropyOneOverSets) {
  auto white = [](uint64_t seed) { return UniformPoints(seed, kWhitePoints, kUnitWindow); };
  auto radial =
      ComputeRadialSpectrum(AveragePeriodogram(kWhiteSets, kWhiteFrequency, kUnitWindow, white));
  ASSERT_TRUE(radial.ok());
  // 32 annuli: a deviation of 4.5 standard errors is a 1-in-10^4 event.
  EXPECT_LT(WorstFlatnessZ(*radial, kWhiteSets), 4.5);
  // Over 25 annuli of ~50..200 values the mean anisotropy is within ~5 % of
  // 1 / S, less the small bias of duplicated values; 20 % is a wide margin.
  EXPECT_NEAR(MeanAnisotropy(*radial), 1.0 / kWhiteSets, 0.2 / kWhiteSets);

  // Planted fault: every point doubled at a distance of 1e-4 L, which doubles
  // the low-frequency power.
  auto doubled = [](uint64_t seed) {
    std::vector<Vec2> points = UniformPoints(seed, kWhitePoints / 2, {0, 0, 0.999, 0.999});
    const size_t half = points.size();
    for (size_t i = 0; i < half; ++i) points.push_back(points[i] + Vec2{1e-4, 1e-4});
    return points;
  };
  auto doubled_radial =
      ComputeRadialSpectrum(AveragePeriodogram(kWhiteSets, kWhiteFrequency, kUnitWindow, doubled));
  EXPECT_GT(WorstFlatnessZ(*doubled_radial, kWhiteSets), 4.5);

  // Planted fault: points on 8 horizontal lines, white along x, a comb along y.
  auto striped = [](uint64_t seed) {
    std::vector<Vec2> points = UniformPoints(seed, kWhitePoints, kUnitWindow);
    for (Vec2& p : points) p.y = (std::floor(p.y * 8) + 0.5) / 8;
    return points;
  };
  auto striped_radial =
      ComputeRadialSpectrum(AveragePeriodogram(kWhiteSets, kWhiteFrequency, kUnitWindow, striped));
  EXPECT_GT(MeanAnisotropy(*striped_radial), 1.2 / kWhiteSets);
}

// The radial binning against a separate, naive one on random power values.
TEST(RadialSpectrumTest, MatchesNaiveAnnulusStatistics) {
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    Rng rng(seed);
    Periodogram periodogram;
    periodogram.max_frequency = 3 + static_cast<int>(rng.Below(20));
    periodogram.set_count = 1;
    for (int i = 0; i < periodogram.side() * periodogram.side(); ++i) {
      periodogram.power.push_back(rng.Uniform(0, 3));
    }
    auto radial = ComputeRadialSpectrum(periodogram);
    ASSERT_TRUE(radial.ok());
    const int k_max = periodogram.max_frequency;
    ASSERT_EQ(radial->frequency.size(), static_cast<size_t>(k_max));
    auto naive_mismatch = [&](const Periodogram& data) {
      double worst = 0;
      for (int r = 1; r <= k_max; ++r) {
        std::vector<double> values;
        for (int ky = -k_max; ky <= k_max; ++ky) {
          for (int kx = -k_max; kx <= k_max; ++kx) {
            const double length = std::hypot(kx, ky);
            if (length >= r - 0.5 && length < r + 0.5) values.push_back(data.At(kx, ky));
          }
        }
        double mean = 0, variance = 0;
        for (double v : values) mean += v / values.size();
        for (double v : values) variance += (v - mean) * (v - mean) / (values.size() - 1);
        worst = std::max(
            {worst, std::abs(mean - radial->mean_power[r - 1]),
             std::abs(10 * std::log10(variance / (mean * mean)) - radial->anisotropy_db[r - 1]),
             std::abs(double(values.size()) - radial->count[r - 1])});
      }
      return worst;
    };
    EXPECT_LT(naive_mismatch(periodogram), 1e-9) << "seed " << seed;
    // Planted fault: one value on annulus 2 changed.
    Periodogram changed = periodogram;
    changed.power[static_cast<size_t>(k_max) * changed.side() + k_max + 2] += 1;
    EXPECT_GT(naive_mismatch(changed), 1e-3) << "seed " << seed;
  }
}

// The peak and the low-frequency power on a spectrum written by hand: the first of two equal
// maxima is the peak, and only the annuli strictly below half its frequency count.
TEST(RadialSpectrumTest, PeakAndLowFrequencyPowerOfAHandWrittenSpectrum) {
  RadialSpectrum spectrum;
  spectrum.frequency = {1, 2, 3, 4, 5, 6, 7, 8};
  spectrum.mean_power = {0.1, 0.3, 0.5, 1.0, 1.5, 2.5, 2.5, 1.0};
  EXPECT_EQ(PeakAnnulus(spectrum), 5u);                            // frequency 6; not the later 7
  EXPECT_DOUBLE_EQ(LowFrequencyPower(spectrum), (0.1 + 0.3) / 2);  // 1 and 2 (3 is not < 3)
  spectrum.mean_power = {3.0, 0.3, 0.5, 1.0, 1.5, 2.5, 2.5, 1.0};
  EXPECT_EQ(PeakAnnulus(spectrum), 0u);
  EXPECT_TRUE(std::isnan(LowFrequencyPower(spectrum)));  // nothing below 0.5
}

TEST(PeriodogramTest, AveragesWeightEachSetOnce) {
  const std::vector<Vec2> a = UniformPoints(1, 10, kUnitWindow),
                          b = UniformPoints(2, 30, kUnitWindow);
  auto pa = ComputePeriodogram(a, kUnitWindow, 4), pb = ComputePeriodogram(b, kUnitWindow, 4);
  ASSERT_TRUE(pa.ok() && pb.ok());
  PeriodogramAverage average;
  ASSERT_TRUE(average.Add(*pa).ok());
  ASSERT_TRUE(average.Add(*pb).ok());
  auto mean = average.Mean();
  ASSERT_TRUE(mean.ok());
  EXPECT_EQ(mean->set_count, 2);
  EXPECT_EQ(mean->point_count, 40);
  EXPECT_DOUBLE_EQ(mean->At(1, -2), (pa->At(1, -2) + pb->At(1, -2)) / 2);
  EXPECT_DOUBLE_EQ(mean->At(0, 0), 20);
}

TEST(PeriodogramTest, RejectsBadInput) {
  const std::vector<Vec2> points{{0.5, 0.5}};
  auto rejects = [](std::span<const Vec2> p, const Rect& window, int k, const std::string& field) {
    auto result = ComputePeriodogram(p, window, k);
    ASSERT_FALSE(result.ok()) << field;
    EXPECT_EQ(result.status().code(), StatusCode::kInvalidArgument);
    EXPECT_NE(result.status().message().find(field), std::string::npos)
        << result.status().message();
  };
  rejects(points, kUnitWindow, 0, "max_frequency");
  rejects(points, kUnitWindow, kMaxPeriodogramFrequency + 1, "max_frequency");
  rejects(points, {0, 0, 1, 2}, 4, "square");
  rejects(points, {0, 0, INFINITY, INFINITY}, 4, "window");
  rejects(points, {1, 1, 0, 0}, 4, "window");
  rejects({}, kUnitWindow, 4, "points");
  const std::vector<Vec2> outside{{0.5, 0.5}, {1.0, 0.5}};
  rejects(outside, kUnitWindow, 4, "points[1]");
  const std::vector<Vec2> not_finite{{NAN, 0.5}};
  rejects(not_finite, kUnitWindow, 4, "points[0]");

  PeriodogramAverage average;
  EXPECT_FALSE(average.Mean().ok());
  auto p4 = ComputePeriodogram(points, kUnitWindow, 4),
       p5 = ComputePeriodogram(points, kUnitWindow, 5);
  ASSERT_TRUE(average.Add(*p4).ok());
  Status mismatch = average.Add(*p5);
  EXPECT_FALSE(mismatch.ok());
  EXPECT_NE(mismatch.message().find("max_frequency"), std::string::npos);
  EXPECT_FALSE(average.Add(Periodogram{}).ok());
  EXPECT_FALSE(ComputeRadialSpectrum(Periodogram{}).ok());
}

}  // namespace
}  // namespace scallop
