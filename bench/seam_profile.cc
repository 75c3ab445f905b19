// Worlds' density against their regions (docs/quality.md, "What remains" under
// Seams, and "Across seams" under Radius fields): what a generator version that
// removes the seam effects must flatten, and a measure that sees them. Over
// WORLDS worlds, in a block of 6 x 6 regions from the origin (every rank):
//   seam     density by signed distance to the nearest seam, in bins of 1/32 of
//            a region's side, out to the middle of a region, positive into the
//            higher-ranked of the two regions the seam parts;
//   rank 0   density by distance to the centre of a rank-0 region (where its
//            run grows from one point), in rings of 1/16 of a side.
// A3 worlds of d = 1 (regions 16 d: bins of d / 2, rings of d), or with RATIO
// noise-field worlds over [1, RATIO] at 90% of the slope bound (regions 6 r_max),
// where a point counts R(p)^2, so that the density is flat wherever the
// spacing changes. Each bin is also given as z: the mean over the worlds of the
// bin's density less the world's own, in standard errors of that mean.
//
// Usage: seam_profile [worlds=200] [first seed=0xa3000] [noise field ratio]
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <vector>

#include "scallop/field/radius_field.h"
#include "scallop/field/value_noise.h"
#include "scallop/plane/plane_engine.h"
#include "scallop/plane/region_layout.h"
#include "scallop/plane/world.h"
#include "tests/seed_statistics.h"

namespace {

using scallop::RegionKey;
using scallop::RegionRank;
using scallop::Vec2;
using scallop::World;

constexpr int kSeamBins = 32;  // over [-side / 2, side / 2)
constexpr int kRings = 8;      // over [0, side / 2)
constexpr int kBlockRegions = 6;

// One bin's density in every world, and less that world's mean density.
struct Bin {
  std::vector<double> density, excess;
  void Add(double bin_density, double world_density) {
    density.push_back(bin_density);
    excess.push_back(bin_density - world_density);
  }
  double Density() const { return scallop::Mean(density); }
  // The mean excess in standard errors of the mean.
  double Z() const {
    const double error = scallop::Spread(excess) / std::sqrt(static_cast<double>(excess.size()));
    return error > 0.0 ? scallop::Mean(excess) / error : 0.0;
  }
};

// Signed distance of p to the nearest seam across `axis` (0: the seams x = side k),
// positive on the higher-ranked side; NaN where that seam is the block's own edge.
double SignedSeamDistance(Vec2 p, int axis, double side) {
  const double along = axis == 0 ? p.x : p.y, across = axis == 0 ? p.y : p.x;
  const double seam_number = std::round(along / side);
  if (seam_number <= 0 || seam_number >= kBlockRegions) return NAN;
  const double seam = side * seam_number;
  const auto low = static_cast<int64_t>(seam_number) - 1;
  const auto row = static_cast<int64_t>(std::floor(across / side));
  const RegionKey below = axis == 0 ? RegionKey{low, row} : RegionKey{row, low};
  const RegionKey above = axis == 0 ? RegionKey{low + 1, row} : RegionKey{row, low + 1};
  return (along - seam) * (RegionRank(above) > RegionRank(below) ? 1.0 : -1.0);
}

// Distance of p to the centre of the rank-0 region of its 2 x 2 block of regions.
double DistanceToRankZeroCentre(Vec2 p, double side) {
  const double period = 2 * side, half = side / 2;
  const double cx = period * std::floor(p.x / period) + half;
  const double cy = period * std::floor(p.y / period) + half;
  return std::hypot(p.x - cx, p.y - cy);
}

// World `seed`: A3 with d = 1, or with ratio > 1 a noise field over [1, ratio] at 90% of the slope
// bound (as the tests' NoiseField).
World MakeWorld(uint64_t seed, double ratio) {
  if (ratio <= 1.0) {
    return *World::Create({.seed = seed, .algorithm = scallop::WorldAlgorithm::kA3});
  }
  scallop::RadiusFieldSpec field{.kind = scallop::RadiusFieldKind::kNoise,
                                 .r_min = 1.0,
                                 .r_max = ratio,
                                 .noise_seed = seed,
                                 .octaves = 3,
                                 .gain = 0.5};
  field.frequency =
      0.9 * scallop::kMaxFieldSlope /
      ((ratio - 1.0) * scallop::FractalValueNoiseSlope(1.0, field.octaves, field.gain));
  return *World::Create({.seed = seed, .radius_field = field});
}

}  // namespace

int main(int argc, char** argv) {
  const int worlds = argc > 1 ? std::atoi(argv[1]) : 200;
  const uint64_t first_seed = argc > 2 ? std::strtoull(argv[2], nullptr, 0) : 0xa3000;
  const double ratio = argc > 3 ? std::atof(argv[3]) : 1.0;
  if (worlds < 2 || !(ratio >= 1.0)) {
    std::fprintf(stderr, "usage: %s [worlds >= 2] [first seed] [noise field ratio > 1]\n", argv[0]);
    return 2;
  }
  std::vector<Bin> seam(kSeamBins), rings(kRings);
  // The spacing unit the distances are printed in: d, or r_max for a field.
  const double unit = ratio > 1.0 ? ratio : 1.0;
  double side = 0.0, density_sum = 0.0;
  scallop::PlaneEngine engine(scallop::PlaneEngineOptions{.threads = 1});
  for (int k = 0; k < worlds; ++k) {
    const World world = MakeWorld(first_seed + static_cast<uint64_t>(k), ratio);
    side = scallop::RegionLayout(world).side();
    const double block = kBlockRegions * side;
    const auto points = engine.Points(world, {0, 0, block, block});
    if (!points.ok()) {
      std::fprintf(stderr, "%s\n", points.status().message().c_str());
      return 1;
    }
    // A point counts R(p)^2 (1 in an A3 world of d = 1).
    const scallop::RadiusField* field = world.radius_field();
    std::vector<double> seam_sums(kSeamBins), ring_sums(kRings);
    double total = 0.0;
    for (const Vec2& p : points->positions) {
      const double r = field != nullptr ? field->Evaluate(p) : 1.0, weight = r * r;
      total += weight;
      for (int axis = 0; axis < 2; ++axis) {
        const double t = SignedSeamDistance(p, axis, side);
        if (std::isnan(t)) continue;
        const int bin = std::clamp(
            static_cast<int>(std::floor(t / side * kSeamBins)) + kSeamBins / 2, 0, kSeamBins - 1);
        seam_sums[bin] += weight;
      }
      const double ring = DistanceToRankZeroCentre(p, side) / side * 2 * kRings;
      if (ring < kRings) ring_sums[static_cast<int>(ring)] += weight;
    }
    const double seam_bin_area = 2 * (kBlockRegions - 1) * block * side / kSeamBins;  // both axes
    const double rank_zero_centres = (kBlockRegions / 2) * (kBlockRegions / 2);
    const double ring_width = side / (2 * kRings);
    const double world_density = total / (block * block);
    density_sum += world_density;
    for (int b = 0; b < kSeamBins; ++b) seam[b].Add(seam_sums[b] / seam_bin_area, world_density);
    for (int r = 0; r < kRings; ++r) {
      const double area =
          rank_zero_centres * std::numbers::pi * (2 * r + 1) * ring_width * ring_width;
      rings[r].Add(ring_sums[r] / area, world_density);
    }
  }
  const char* unit_name = ratio > 1.0 ? "r_max" : "d";
  std::printf("%d %s worlds from seed %#llx, regions %g %s, blocks of %d x %d regions: %.4f %s\n",
              worlds, ratio > 1.0 ? "noise-field" : "A3",
              static_cast<unsigned long long>(first_seed), side / unit, unit_name, kBlockRegions,
              kBlockRegions, density_sum / worlds,
              ratio > 1.0 ? "points a unit area, each counting R^2" : "points per d^2");
  std::printf("seam (from, %s; density; z):", unit_name);
  for (int b = 0; b < kSeamBins; ++b) {
    const double from = (b - kSeamBins / 2) * side / kSeamBins / unit;
    std::printf(" %+.2f:%.3f:%+.1f", from, seam[b].Density(), seam[b].Z());
  }
  std::printf("\nrank 0 (ring from, %s; density; z):", unit_name);
  for (int r = 0; r < kRings; ++r) {
    std::printf(" %.2f:%.3f:%+.1f", r * side / (2 * kRings) / unit, rings[r].Density(),
                rings[r].Z());
  }
  std::printf("\n");
  return 0;
}
