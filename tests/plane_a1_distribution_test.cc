// A1 worlds at density 2 against bounded exact A1 (dart throwing run to exhaustion): away from
// seams a world's windows must have the same rho and g(r) within 3 standard errors over the
// seeds, and the density must stay flat across seams, into either neighbour (the paper's A1
// regions of version 3 fail that). The larger run of docs/quality.md ("A1 worlds are dart
// throwing") is scripts/a1-plane-against-bounded.sh.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "scallop/plane/plane_engine.h"
#include "scallop/plane/region_layout.h"
#include "scallop/random/rng.h"
#include "scallop/sampling/sampler.h"
#include "tests/seed_statistics.h"
#include "tests/test_worlds.h"

namespace scallop {
namespace {

// d = 1, so regions are 16 x 16; the block [0, 48)^2 holds 3 x 3 of them (every rank). Windows
// are the regions' interiors [4, 12)^2: 4 d from every seam, and g(r) out to 3 d from a point
// in them reads points of the block only.
constexpr double kSide = 16.0, kBlock = 48.0, kInset = 4.0;
constexpr double kReach = 3.0;
constexpr int kBins = 30;  // g(r) over [0, 3 d) in bins of 0.1 d
// The reference: bounded exact A1 on a 40 d torus (no edges at all).
constexpr Domain kTorus{{0.0, 0.0, 40.0, 40.0}, true};
// 3 standard errors of the difference of the two means (Welch), as the issue asks; per bin of
// g(r) as well. Fixed seeds: a pass or fail reproduces.
constexpr double kMaxZ = 3.0;

int Seeds(int otherwise) {
  const char* text = std::getenv("PLANE_A1_SEEDS");
  return text != nullptr ? std::atoi(text) : otherwise;
}

// Per seed: rho of the judged area, and g(r) around its points.
struct Measured {
  std::vector<double> rho;
  std::vector<std::vector<double>> g = std::vector<std::vector<double>>(kBins);
};

// Adds one seed: `centres` are the judged points (in an area of `area` d^2), `others` every
// point within kReach of them; `offset(p, q)` is q - p (with wrap-around on the torus).
template <typename Offset>
void AddSeed(const std::vector<Vec2>& centres, const std::vector<Vec2>& others, double area,
             Offset offset, Measured& measured) {
  const double density = static_cast<double>(centres.size()) / area;
  // rho = d / d_max with d_max = sqrt(2 / (sqrt(3) density)).
  measured.rho.push_back(1.0 / std::sqrt(2.0 / (std::sqrt(3.0) * density)));
  std::vector<double> counts(kBins, 0.0);
  for (const Vec2& p : centres) {
    for (const Vec2& q : others) {
      const Vec2 o = offset(p, q);
      const double r = std::sqrt(o.x * o.x + o.y * o.y);
      if (r > 0.0 && r < kReach) counts[static_cast<size_t>(r / kReach * kBins)] += 1;
    }
  }
  for (int b = 0; b < kBins; ++b) {
    const double r0 = b * kReach / kBins, r1 = (b + 1) * kReach / kBins;
    const double expected = density * M_PI * (r1 * r1 - r0 * r0);
    measured.g[b].push_back(counts[b] / static_cast<double>(centres.size()) / expected);
  }
}

Measured MeasureTorus(int seeds) {
  Measured measured;
  for (int k = 0; k < seeds; ++k) {
    SamplerOptions options;
    options.algorithm = Algorithm::kA1;
    options.density = 2.0;
    options.domain = kTorus;
    options.seed = HashWords({0x7a1, static_cast<uint64_t>(k)});
    StatusOr<std::vector<Vec2>> points = Sample(options);
    EXPECT_TRUE(points.ok()) << points.status().message();
    const double side = kTorus.rect.Width();
    AddSeed(
        *points, *points, kTorus.rect.Area(),
        [side](Vec2 p, Vec2 q) {
          Vec2 o = q - p;
          o.x -= side * std::round(o.x / side);
          o.y -= side * std::round(o.y / side);
          return o;
        },
        measured);
  }
  return measured;
}

// The block [0, 48)^2 of A1 worlds 0xa1000 + k.
std::vector<std::vector<Vec2>> WorldBlocks(int seeds, double density) {
  PlaneEngine engine(PlaneEngineOptions{.threads = 1});
  std::vector<std::vector<Vec2>> blocks;
  for (int k = 0; k < seeds; ++k) {
    auto points = engine.Points(ValidWorld({.seed = 0xa1000 + static_cast<uint64_t>(k),
                                            .algorithm = WorldAlgorithm::kA1,
                                            .density = density}),
                                {0, 0, kBlock, kBlock});
    EXPECT_TRUE(points.ok()) << points.status().message();
    blocks.push_back(points->positions);
  }
  return blocks;
}

bool InInterior(Vec2 p) {
  const double x = p.x - kSide * std::floor(p.x / kSide), y = p.y - kSide * std::floor(p.y / kSide);
  return x >= kInset && x < kSide - kInset && y >= kInset && y < kSide - kInset;
}

Measured MeasureInteriors(const std::vector<std::vector<Vec2>>& blocks) {
  Measured measured;
  for (const std::vector<Vec2>& block : blocks) {
    std::vector<Vec2> centres;
    for (const Vec2& p : block) {
      if (InInterior(p)) centres.push_back(p);
    }
    const double window = kSide - 2 * kInset;
    AddSeed(
        centres, block, 9 * window * window, [](Vec2 p, Vec2 q) { return q - p; }, measured);
  }
  return measured;
}

// Largest z over rho and the bins of g(r), printed with the figures docs/quality.md quotes.
double WorstZ(const Measured& world, const Measured& bounded, const std::string& what) {
  double worst = ZScore(world.rho, bounded.rho);
  std::printf("%s: rho %.5f against bounded %.5f (%zu and %zu seeds), %.2f standard errors\n",
              what.c_str(), Mean(world.rho), Mean(bounded.rho), world.rho.size(),
              bounded.rho.size(), worst);
  int worst_bin = 0;
  double worst_g = 0;
  int beyond = 0;
  for (int b = 0; b < kBins; ++b) {
    const double z = ZScore(world.g[b], bounded.g[b]);
    beyond += z > kMaxZ;
    if (z > worst_g) worst_g = z, worst_bin = b;
  }
  std::printf(
      "%s: g(r) worst bin %.2f d, %.4f against %.4f, %.2f standard errors; %d of %d bins "
      "beyond %.0f\n",
      what.c_str(), (worst_bin + 0.5) * kReach / kBins, Mean(world.g[worst_bin]),
      Mean(bounded.g[worst_bin]), worst_g, beyond, kBins, kMaxZ);
  return std::max(worst, worst_g);
}

// Points per d^2 by signed distance to the nearest seam (positive into the higher-ranked
// region), in bins of 0.5 d over [-8, 8), over the vertical and horizontal seams inside the
// block, each world's bins against its own block's density. Prints the densities and returns the
// largest |z| over the bins (the mean of the per-world differences in standard errors).
double WorstSeamZ(const std::vector<std::vector<Vec2>>& blocks, const std::string& what) {
  constexpr int kBinsAcross = 32;
  // Two seams of each axis, 48 d long each, a bin 0.5 d wide.
  constexpr double kBinArea = 2 * 2 * kBlock * 0.5;
  std::vector<std::vector<double>> differences(kBinsAcross);
  std::vector<double> density(kBinsAcross, 0.0);
  for (const std::vector<Vec2>& block : blocks) {
    std::vector<double> counts(kBinsAcross, 0.0);
    for (const Vec2& p : block) {
      for (int axis = 0; axis < 2; ++axis) {
        const double along = axis == 0 ? p.x : p.y, across = axis == 0 ? p.y : p.x;
        const double seam = kSide * std::round(along / kSide);
        if (seam <= 0.0 || seam >= kBlock) continue;  // only the seams inside the block
        const auto low = static_cast<int64_t>(seam / kSide) - 1;
        const auto row = static_cast<int64_t>(std::floor(across / kSide));
        const RegionKey below = axis == 0 ? RegionKey{low, row} : RegionKey{row, low};
        const RegionKey above = axis == 0 ? RegionKey{low + 1, row} : RegionKey{row, low + 1};
        const double t = (along - seam) * (RegionRank(above) > RegionRank(below) ? 1.0 : -1.0);
        counts[static_cast<size_t>(std::floor(t * 2)) + kBinsAcross / 2] += 1;
      }
    }
    const double mean = static_cast<double>(block.size()) / (kBlock * kBlock);
    for (int b = 0; b < kBinsAcross; ++b) {
      differences[b].push_back(counts[b] / kBinArea - mean);
      density[b] += counts[b] / kBinArea / static_cast<double>(blocks.size());
    }
  }
  std::printf(
      "%s, %zu worlds: points per d^2 by signed distance to a seam (0.5 d bins, -8..8 d; "
      "positive into the higher-ranked region), and z against the block's density:\n",
      what.c_str(), blocks.size());
  double worst = 0.0;
  for (int b = 0; b < kBinsAcross; ++b) std::printf(" %.3f", density[b]);
  std::printf("\n");
  for (int b = 0; b < kBinsAcross; ++b) {
    const double z = Mean(differences[b]) /
                     (Spread(differences[b]) / std::sqrt(static_cast<double>(blocks.size())));
    std::printf(" %+.1f", z);
    worst = std::max(worst, std::abs(z));
  }
  std::printf("\n");
  return worst;
}

// Region interiors have bounded exact A1's rho and g(r); the density is flat across seams. Over
// 48 worlds one 0.5 d bin holds about 1,600 points, and its per-world difference from the
// block's density has a standard error of about 1.5%: the wall echo of version 3 (8% fewer
// points 5.5 to 6 d into the higher-ranked region) is 4 to 5 of them. kMaxSeamZ over 32 bins:
// a flat profile exceeds it with a chance under 1% (t, 47 degrees of freedom).
constexpr double kMaxSeamZ = 4.0;

TEST(PlaneA1DistributionTest, WorldInteriorsAreBoundedExactA1AndSeamsAreFlat) {
  const int seeds = Seeds(48);
  const Measured bounded = MeasureTorus(seeds);
  const std::vector<std::vector<Vec2>> blocks = WorldBlocks(seeds, 2.0);
  EXPECT_LE(WorstZ(MeasureInteriors(blocks), bounded, "a1 world interiors"), kMaxZ);
  EXPECT_LE(WorstSeamZ(blocks, "a1 worlds"), kMaxSeamZ);
}

// The paper's A1 in world regions, as version 3 ran it at density 2 (density 1.99 still runs
// it): its growth front runs to the region's sampled edge, 6.5 d into the neighbour, and the
// seam check must see it (over 48 worlds: z -9.6 at 5.5 to 6 d, +47 at 6 to 6.5 d, -57 beyond;
// 12 worlds are plenty).
TEST(PlaneA1DistributionTest, SeamCheckSeesThePapersWallEcho) {
  EXPECT_GT(WorstSeamZ(WorldBlocks(12, 1.99), "the paper's a1 worlds (density 1.99)"), kMaxSeamZ);
}

}  // namespace
}  // namespace scallop
