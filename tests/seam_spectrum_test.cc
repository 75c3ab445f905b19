// Seamlessness seen in the spectrum: windows centred on region seams and
// corners of a world against windows inside regions, over many seeds. The
// radial power and anisotropy must differ by no more than the spread between
// seeds allows, and planted seam defects must not pass.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "scallop/analysis/periodogram.h"
#include "scallop/analysis/radial_spectrum.h"
#include "scallop/plane/plane_engine.h"
#include "scallop/plane/region_layout.h"
#include "scallop/random/rng.h"
#include "scallop/sampling/sampler.h"
#include "tests/test_worlds.h"

namespace scallop {
namespace {

// d = 1, so regions are 16 x 16. Windows are 8 x 8: inside a region they sit
// 4 d from every seam, so a defect along seams cannot reach them, not even
// through the periodogram's wrap-around at the window's edges.
constexpr double kSide = 16.0, kWindow = 8.0;
constexpr int kMaxFrequency = 20;  // 2.5 cycles per d
constexpr int kBandWidth = 2;      // annuli per band: 10 bands of 0.25 / d
// Fixed before looking at the faults: 10 bands x 2 measures x 2 window
// classes; a seamless world exceeds 4 standard errors somewhere with a chance
// of 1 to 2 % (t with 23..47 degrees of freedom). The seeds are fixed, so
// the test does not flake.
constexpr double kMaxZ = 4.0;

enum class WindowClass { kInterior, kSeam, kCorner };

// Four windows of each class in the block [0, 48)^2 of regions, covering every
// rank: interiors of regions (0,0), (1,0), (0,1), (1,1); the seams between
// them; the four corners inside the block.
std::vector<Vec2> WindowCentres(WindowClass window_class) {
  switch (window_class) {
    case WindowClass::kInterior:
      return {{8, 8}, {24, 8}, {8, 24}, {24, 24}};
    case WindowClass::kSeam:
      return {{16, 8}, {16, 24}, {8, 16}, {24, 16}};
    case WindowClass::kCorner:
      return {{16, 16}, {32, 16}, {16, 32}, {32, 32}};
  }
  return {};
}

// The block [0, 48)^2 of worlds 1000, 1001, ...: one point set per seed.
using Blocks = std::vector<std::vector<Vec2>>;

Blocks WorldBlocks(WorldAlgorithm algorithm, int seeds) {
  PlaneEngine engine(PlaneEngineOptions{.threads = 1});
  Blocks blocks;
  for (int s = 0; s < seeds; ++s) {
    auto world =
        engine.Points(ValidWorld({.seed = 1000 + static_cast<uint64_t>(s), .algorithm = algorithm}),
                      {0, 0, 3 * kSide, 3 * kSide});
    EXPECT_TRUE(world.ok()) << world.status().message();
    blocks.push_back(world->positions);
  }
  return blocks;
}

// Planted defect: the points within d / 2 of a seam dropped.
Blocks WithGapsAlongSeams(const Blocks& blocks) {
  Blocks gapped;
  for (const std::vector<Vec2>& block : blocks) {
    gapped.emplace_back();
    for (const Vec2& p : block) {
      const double to_seam_x = std::abs(p.x - kSide * std::round(p.x / kSide));
      const double to_seam_y = std::abs(p.y - kSide * std::round(p.y / kSide));
      if (std::min(to_seam_x, to_seam_y) >= 0.5) gapped.back().push_back(p);
    }
  }
  return gapped;
}

// Planted defect: every region sampled alone, as a naive tiling would,
// ignoring its neighbours.
Blocks IndependentRegionBlocks(WorldAlgorithm algorithm, int seeds) {
  Blocks blocks;
  for (int s = 0; s < seeds; ++s) {
    blocks.emplace_back();
    for (int j = 0; j < 3; ++j) {
      for (int i = 0; i < 3; ++i) {
        SamplerOptions options;
        options.algorithm = SamplerAlgorithm(algorithm);
        options.domain.rect = {i * kSide, j * kSide, (i + 1) * kSide, (j + 1) * kSide};
        options.seed = HashWords({1000 + static_cast<uint64_t>(s), uint64_t(i), uint64_t(j)});
        auto region = Sample(options);
        EXPECT_TRUE(region.ok());
        blocks.back().insert(blocks.back().end(), region->begin(), region->end());
      }
    }
  }
  return blocks;
}

// Per seed: radial power and anisotropy, in bands, of the average periodogram
// of that seed's four windows of one class.
struct BandedSpectrum {
  std::vector<double> power, anisotropy_db;
};

BandedSpectrum ClassSpectrum(const std::vector<Vec2>& points, WindowClass window_class) {
  PeriodogramAverage average;
  for (const Vec2& centre : WindowCentres(window_class)) {
    const Rect window{centre.x - kWindow / 2, centre.y - kWindow / 2, centre.x + kWindow / 2,
                      centre.y + kWindow / 2};
    std::vector<Vec2> inside;
    for (const Vec2& p : points) {
      if (window.Contains(p)) inside.push_back(p);
    }
    auto periodogram = ComputePeriodogram(inside, window, kMaxFrequency);
    EXPECT_TRUE(periodogram.ok()) << periodogram.status().message();
    EXPECT_TRUE(average.Add(*periodogram).ok());
  }
  auto radial = ComputeRadialSpectrum(*average.Mean());
  EXPECT_TRUE(radial.ok());
  BandedSpectrum banded;
  for (size_t start = 0; start < radial->frequency.size(); start += kBandWidth) {
    double power = 0, anisotropy = 0;
    for (size_t r = start; r < start + kBandWidth; ++r) {
      power += radial->mean_power[r] / kBandWidth;
      anisotropy += radial->anisotropy_db[r] / kBandWidth;
    }
    banded.power.push_back(power);
    banded.anisotropy_db.push_back(anisotropy);
  }
  return banded;
}

// Largest |mean difference| / standard error over seeds, over bands, of the
// paired per-seed differences between `window_class` and interior windows,
// for power and anisotropy. Prints the bands for the record.
double WorstZ(const Blocks& blocks, WindowClass window_class, const std::string& what) {
  const size_t bands = kMaxFrequency / kBandWidth;
  const int seeds = static_cast<int>(blocks.size());
  std::vector<double> sum(2 * bands, 0), squares(2 * bands, 0);
  for (const std::vector<Vec2>& points : blocks) {
    const BandedSpectrum inside = ClassSpectrum(points, WindowClass::kInterior);
    const BandedSpectrum across = ClassSpectrum(points, window_class);
    for (size_t b = 0; b < bands; ++b) {
      const double power = across.power[b] - inside.power[b];
      const double anisotropy = across.anisotropy_db[b] - inside.anisotropy_db[b];
      sum[b] += power, squares[b] += power * power;
      sum[bands + b] += anisotropy, squares[bands + b] += anisotropy * anisotropy;
    }
  }
  double worst = 0;
  std::printf("%s, %s windows - interior, %d seeds: z per band (power | anisotropy)\n",
              what.c_str(), window_class == WindowClass::kSeam ? "seam" : "corner", seeds);
  for (size_t i = 0; i < 2 * bands; ++i) {
    const double mean = sum[i] / seeds;
    const double variance = (squares[i] - seeds * mean * mean) / (seeds - 1);
    const double z = mean / std::sqrt(variance / seeds);
    std::printf(" %+5.1f%s", z, i + 1 == bands ? " |" : "");
    worst = std::max(worst, std::abs(z));
  }
  std::printf("\n");
  return worst;
}

// Density (points per d^2) by distance to the nearest vertical seam, in bins
// of d / 4 up to 3 d, then the mean beyond 3 d as the last entry, over the
// block [0, 48)^2 of `seeds` worlds. Printed for docs/quality.md.
std::vector<double> SeamDensityProfile(const Blocks& blocks, const std::string& what) {
  constexpr int kBins = 12;
  const int seeds = static_cast<int>(blocks.size());
  std::vector<double> counts(kBins + 1, 0);
  for (const std::vector<Vec2>& block : blocks) {
    for (const Vec2& p : block) {
      const double to_seam = std::abs(p.x - kSide * std::round(p.x / kSide));
      counts[std::min(kBins, static_cast<int>(to_seam * 4))] += 1;
    }
  }
  // The block has seams at x = 0, 16, 32 and 48: six sides of d / 4 per bin
  // and 48 d tall; beyond 3 d, 3 strips of 10 d.
  std::printf("%s density by distance to a seam, %d worlds (bins of d/4, then beyond 3 d):\n",
              what.c_str(), seeds);
  std::vector<double> density;
  for (int b = 0; b <= kBins; ++b) {
    const double area = (b < kBins ? 6 * 0.25 : 3 * 10.0) * 3 * kSide * seeds;
    density.push_back(counts[b] / area);
    std::printf(" %.3f", density.back());
  }
  std::printf("\n");
  return density;
}

// The growing regions of region_generator.h leave no layer along seams (the
// old generator, which sampled a region against its edges as against walls,
// had 47 % more A1 points within d / 4 of a seam than beyond 3 d); the
// planted defects are caught.
TEST(SeamSpectrumTest, A1SeamsAndCornersLookLikeRegionInteriors) {
  const Blocks blocks = WorldBlocks(WorldAlgorithm::kA1, 24);
  const std::vector<double> density = SeamDensityProfile(blocks, "a1");
  EXPECT_NEAR(density.front(), density.back(), 0.08 * density.back());
  EXPECT_LT(WorstZ(blocks, WindowClass::kSeam, "a1"), kMaxZ);
  EXPECT_LT(WorstZ(blocks, WindowClass::kCorner, "a1"), kMaxZ);
  EXPECT_GT(WorstZ(WithGapsAlongSeams(blocks), WindowClass::kSeam, "a1 with gaps"), kMaxZ);
  EXPECT_GT(WorstZ(IndependentRegionBlocks(WorldAlgorithm::kA1, 24), WindowClass::kCorner,
                   "a1 regions alone"),
            kMaxZ);
}

// A2 worlds: no seam layer (the density profile is flat) and the planted
// defects are caught, as for A1. But A2 is not seamless in the spectrum, and
// this test does not claim it: windows where growth fronts meet (corners,
// less so seams) put more power at 0.5..0.75 / d and less at 0.75..1 / d
// than region interiors, z = +2.7 / -4.4 over 24 seeds and +5.9 / -6.6 over
// 72, growing as a real difference does. A2 picks candidates uniformly, so
// its statistics depend on the shape of the front (docs/quality.md, "Seams").
// The printed z values keep the measurement in the log.
TEST(SeamSpectrumTest, A2HasNoSeamLayerButItsCornersDiffer) {
  const Blocks blocks = WorldBlocks(WorldAlgorithm::kA2, 24);
  const std::vector<double> density = SeamDensityProfile(blocks, "a2");
  EXPECT_NEAR(density.front(), density.back(), 0.08 * density.back());
  WorstZ(blocks, WindowClass::kSeam, "a2");  // printed, not judged: see above
  WorstZ(blocks, WindowClass::kCorner, "a2");
  const Blocks gapped = WithGapsAlongSeams(blocks);
  const std::vector<double> gapped_density = SeamDensityProfile(gapped, "a2 with gaps");
  EXPECT_LT(gapped_density.front(), 0.92 * gapped_density.back());
  EXPECT_GT(WorstZ(gapped, WindowClass::kSeam, "a2 with gaps"), kMaxZ);
}

// A3 worlds, at 48 seeds: the old generator's seam layer (20 % more points
// within d / 4 of a seam, seam windows 6 standard errors off at 0.375..0.5
// / d) is gone. A bin of the profile holds ~2000 points over 48 worlds, so
// 5 % is ~2 standard errors.
TEST(SeamSpectrumTest, A3SeamsAndCornersLookLikeRegionInteriors) {
  const Blocks blocks = WorldBlocks(WorldAlgorithm::kA3, 48);
  const std::vector<double> density = SeamDensityProfile(blocks, "a3");
  EXPECT_NEAR(density.front(), density.back(), 0.05 * density.back());
  EXPECT_LT(WorstZ(blocks, WindowClass::kSeam, "a3"), kMaxZ);
  EXPECT_LT(WorstZ(blocks, WindowClass::kCorner, "a3"), kMaxZ);

  const Blocks gapped = WithGapsAlongSeams(blocks);
  const std::vector<double> gapped_density = SeamDensityProfile(gapped, "a3 with gaps");
  EXPECT_LT(gapped_density.front(), 0.95 * gapped_density.back());
  EXPECT_GT(WorstZ(gapped, WindowClass::kCorner, "a3 with gaps"), kMaxZ);
  const Blocks alone = IndependentRegionBlocks(WorldAlgorithm::kA3, 48);
  EXPECT_GT(WorstZ(alone, WindowClass::kSeam, "a3 regions alone"), kMaxZ);
}

}  // namespace
}  // namespace scallop
