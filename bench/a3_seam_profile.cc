// A3 worlds' density against the regions (docs/quality.md, "What remains"):
// what a generator version that removes A3's seam effects must flatten, and
// a measure that sees them. Over WORLDS worlds (d = 1, regions 16 d), in the
// block [0, 96)^2 of each (6 x 6 regions, every rank):
//   seam     points per d^2 by signed distance to the nearest seam, in 0.5 d
//            bins from -8 d to 8 d (the middle of a region), positive into
//            the higher-ranked of the two regions the seam parts;
//   rank 0   points per d^2 by distance to the centre of a rank-0 region (where
//            its run grows from one point), in 1 d rings out to 8 d.
// Each bin is also given as z: the mean over the worlds of the bin's density
// less the world's own, in standard errors of that mean.
//
// Usage: a3_seam_profile [worlds=200] [first seed=0xa3000]
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <vector>

#include "scallop/plane/plane_engine.h"
#include "scallop/plane/region_layout.h"
#include "scallop/plane/world.h"

namespace {

using scallop::RegionKey;
using scallop::RegionRank;
using scallop::Vec2;

constexpr double kRegionSide = scallop::kRegionSideInD;  // d = 1
constexpr double kBlock = 96.0;
constexpr int kSeamBins = 32;  // 0.5 d each over [-8, 8)
constexpr int kRings = 8;      // 1 d each over [0, 8)

// One bin's density in every world, less that world's mean density.
struct Bin {
  double density_sum = 0.0;
  std::vector<double> excess;
  void Add(double density, double world_density) {
    density_sum += density;
    excess.push_back(density - world_density);
  }
  double Density() const { return density_sum / static_cast<double>(excess.size()); }
  // The mean excess in standard errors of the mean.
  double Z() const {
    const auto n = static_cast<double>(excess.size());
    double mean = 0.0, square = 0.0;
    for (double e : excess) mean += e / n;
    for (double e : excess) square += (e - mean) * (e - mean);
    const double error = std::sqrt(square / (n - 1) / n);
    return error > 0.0 ? mean / error : 0.0;
  }
};

// Signed distance of p to the nearest seam across `axis` (0: the seams x = 16 k),
// positive on the higher-ranked side; NaN where that seam is the block's own edge.
double SignedSeamDistance(Vec2 p, int axis) {
  const double along = axis == 0 ? p.x : p.y, across = axis == 0 ? p.y : p.x;
  const double seam = kRegionSide * std::round(along / kRegionSide);
  if (seam <= 0.0 || seam >= kBlock) return NAN;
  const auto low = static_cast<int64_t>(seam / kRegionSide) - 1;
  const auto row = static_cast<int64_t>(std::floor(across / kRegionSide));
  const RegionKey below = axis == 0 ? RegionKey{low, row} : RegionKey{row, low};
  const RegionKey above = axis == 0 ? RegionKey{low + 1, row} : RegionKey{row, low + 1};
  return (along - seam) * (RegionRank(above) > RegionRank(below) ? 1.0 : -1.0);
}

// Distance of p to the centre of the rank-0 region of its 2 x 2 block of regions.
double DistanceToRankZeroCentre(Vec2 p) {
  const double period = 2 * kRegionSide, half = kRegionSide / 2;
  const double cx = period * std::floor(p.x / period) + half;
  const double cy = period * std::floor(p.y / period) + half;
  return std::hypot(p.x - cx, p.y - cy);
}

}  // namespace

int main(int argc, char** argv) {
  const int worlds = argc > 1 ? std::atoi(argv[1]) : 200;
  const uint64_t first_seed = argc > 2 ? std::strtoull(argv[2], nullptr, 0) : 0xa3000;
  if (worlds < 2) {
    std::fprintf(stderr, "usage: %s [worlds >= 2] [first seed]\n", argv[0]);
    return 2;
  }
  std::vector<Bin> seam(kSeamBins), rings(kRings);
  const double interior_seams = kBlock / kRegionSide - 1;
  const double seam_bin_area = 2 * interior_seams * kBlock * 0.5;  // both axes
  const double rank_zero_centres = (kBlock / (2 * kRegionSide)) * (kBlock / (2 * kRegionSide));
  double density_sum = 0.0;
  scallop::PlaneEngine engine(scallop::PlaneEngineOptions{.threads = 1});
  for (int k = 0; k < worlds; ++k) {
    const scallop::World world = *scallop::World::Create(
        {.seed = first_seed + static_cast<uint64_t>(k), .algorithm = scallop::WorldAlgorithm::kA3});
    const auto points = engine.Points(world, {0, 0, kBlock, kBlock});
    if (!points.ok()) {
      std::fprintf(stderr, "%s\n", points.status().message().c_str());
      return 1;
    }
    std::vector<double> seam_counts(kSeamBins), ring_counts(kRings);
    for (const Vec2& p : points->positions) {
      for (int axis = 0; axis < 2; ++axis) {
        const double t = SignedSeamDistance(p, axis);
        if (std::isnan(t)) continue;
        const int bin =
            std::clamp(static_cast<int>(std::floor(2 * t)) + kSeamBins / 2, 0, kSeamBins - 1);
        seam_counts[bin] += 1;
      }
      const double r = DistanceToRankZeroCentre(p);
      if (r < kRings) ring_counts[static_cast<int>(r)] += 1;
    }
    const double world_density = static_cast<double>(points->positions.size()) / (kBlock * kBlock);
    density_sum += world_density;
    for (int b = 0; b < kSeamBins; ++b) seam[b].Add(seam_counts[b] / seam_bin_area, world_density);
    for (int r = 0; r < kRings; ++r) {
      const double area = rank_zero_centres * std::numbers::pi * (2 * r + 1);
      rings[r].Add(ring_counts[r] / area, world_density);
    }
  }
  std::printf("%d A3 worlds from seed %#llx, block [0, %g)^2: %.4f points per d^2\n", worlds,
              static_cast<unsigned long long>(first_seed), kBlock, density_sum / worlds);
  std::printf("seam (from, d; density; z):");
  for (int b = 0; b < kSeamBins; ++b) {
    std::printf(" %+.1f:%.3f:%+.1f", (b - kSeamBins / 2) / 2.0, seam[b].Density(), seam[b].Z());
  }
  std::printf("\nrank 0 (ring, d; density; z):");
  for (int r = 0; r < kRings; ++r) {
    std::printf(" %d:%.3f:%+.1f", r, rings[r].Density(), rings[r].Z());
  }
  std::printf("\n");
  return 0;
}
