// A world's density against its regions' layout (docs/quality.md, "The whole profile" under
// Seams, "Across seams" under Radius fields and under Layered worlds), over many worlds: what a
// generator version that removes the seam effects must flatten. Measured in the block of 6 x 6
// regions from the origin (every rank):
//   seam    density by signed distance to the nearest seam, in bins of 1/32 of a region's side,
//           out to the middle of a region, positive into the higher-ranked of the two regions
//           the seam parts;
//   rank 0  density by distance to the centre of a rank-0 region (where its run grows from one
//           point), in rings of 1/16 of a side.
// A point counts its spacing squared (R(p)^2 in a radius-field world), so that the density is in
// points per spacing^2 and flat wherever the spacing changes. bench/seam_profile prints it;
// tests/seam_profile_test.cc holds it to the current generator's.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "scallop/field/radius_field.h"
#include "scallop/field/value_noise.h"
#include "scallop/plane/region_layout.h"
#include "scallop/plane/world.h"
#include "tests/seed_statistics.h"

namespace scallop {

// World `seed` of a profile: A3 with d = 1, or with ratio > 1 a noise field over [1, ratio] at
// 90% of the slope bound (as the tests' NoiseField).
inline StatusOr<World> SeamProfileWorld(uint64_t seed, double ratio) {
  if (ratio <= 1.0) return World::Create({.seed = seed, .algorithm = WorldAlgorithm::kA3});
  RadiusFieldSpec field{.kind = RadiusFieldKind::kNoise,
                        .r_min = 1.0,
                        .r_max = ratio,
                        .noise_seed = seed,
                        .octaves = 3,
                        .gain = 0.5};
  field.frequency = 0.9 * kMaxFieldSlope /
                    ((ratio - 1.0) * FractalValueNoiseSlope(1.0, field.octaves, field.gain));
  return World::Create({.seed = seed, .radius_field = field});
}

// World `seed` of a profile of A1 or A2 at `density` (r' = density d), d = 1.
inline StatusOr<World> SeamProfileWorld(uint64_t seed, WorldAlgorithm algorithm, double density) {
  return World::Create({.seed = seed, .algorithm = algorithm, .density = density});
}

// The forest of docs/quality.md's "Layered worlds" with seed `seed`: trees 8, bushes 3, rocks 1.5,
// default D.
inline StatusOr<World> SeamProfileForest(uint64_t seed) {
  WorldSpec spec{.seed = seed};
  spec.layers = {{.name = "trees", .min_distance = 8},
                 {.name = "bushes", .min_distance = 3},
                 {.name = "rocks", .min_distance = 1.5}};
  return World::Create(spec);
}

class SeamProfile {
 public:
  static constexpr int kSeamBins = 32;  // over [-side / 2, side / 2)
  static constexpr int kRings = 8;      // over [0, side / 2)
  static constexpr int kBlockRegions = 6;

  // One bin's density in every world, and less that world's mean density.
  struct Bin {
    std::vector<double> density, excess;
    double Density() const { return Mean(density); }
    // The mean excess in standard errors of that mean.
    double Z() const {
      const double error = Spread(excess) / std::sqrt(static_cast<double>(excess.size()));
      return error > 0.0 ? Mean(excess) / error : 0.0;
    }
  };

  explicit SeamProfile(double region_side) : side_(region_side) {}

  double side() const { return side_; }
  double block() const { return kBlockRegions * side_; }
  double MeanDensity() const { return density_sum_ / worlds_; }
  // A bin's mean excess as a fraction of the mean density: -0.05 is 5% under.
  double RelativeExcess(const Bin& bin) const { return Mean(bin.excess) / MeanDensity(); }
  // The standard error of that fraction.
  double RelativeError(const Bin& bin) const {
    return Spread(bin.excess) / std::sqrt(static_cast<double>(bin.excess.size())) / MeanDensity();
  }
  const std::vector<Bin>& seam() const { return seam_; }
  const std::vector<Bin>& rings() const { return rings_; }
  // Where bin b and ring r start: signed distance to the seam, distance to the centre.
  double SeamBinFrom(int b) const { return (b - kSeamBins / 2) * side_ / kSeamBins; }
  double RingFrom(int r) const { return r * side_ / (2 * kRings); }
  // The area of ring r about one centre.
  double RingArea(int r) const {
    return std::numbers::pi * (2 * r + 1) * RingFrom(1) * RingFrom(1);
  }

  // The centres of the block's rank-0 regions, (0, 0), (2, 0), ... in regions.
  std::vector<Vec2> RankZeroCentres() const {
    std::vector<Vec2> centres;
    for (int a = 0; a < kBlockRegions / 2; ++a) {
      for (int b = 0; b < kBlockRegions / 2; ++b) {
        centres.push_back({(2 * a + 0.5) * side_, (2 * b + 0.5) * side_});
      }
    }
    return centres;
  }

  // A point's weight in `world` (the world the points are of, or a layer's world): its spacing
  // squared, R(p)^2 or d^2, so that densities are in points per spacing^2.
  static double Weight(const World& world, Vec2 p) {
    const double r =
        world.radius_field() ? world.radius_field()->Evaluate(p) : world.min_distance();
    return r * r;
  }

  // One world's points in [0, block())^2.
  void AddWorld(const std::vector<Vec2>& positions, const World& world) {
    std::vector<double> seam_sums(kSeamBins), ring_sums(kRings);
    double total = 0.0;
    for (const Vec2& p : positions) {
      const double weight = Weight(world, p);
      total += weight;
      for (int axis = 0; axis < 2; ++axis) {
        const double t = SignedSeamDistance(p, axis);
        if (std::isnan(t)) continue;
        const int bin = std::clamp(
            static_cast<int>(std::floor(t / side_ * kSeamBins)) + kSeamBins / 2, 0, kSeamBins - 1);
        seam_sums[bin] += weight;
      }
      const double ring = DistanceToRankZeroCentre(p) / side_ * 2 * kRings;
      if (ring < kRings) ring_sums[static_cast<int>(ring)] += weight;
    }
    const double seam_bin_area = 2 * (kBlockRegions - 1) * block() * side_ / kSeamBins;
    const double rank_zero_centres = (kBlockRegions / 2) * (kBlockRegions / 2);
    const double world_density = total / (block() * block());
    density_sum_ += world_density;
    ++worlds_;
    for (int b = 0; b < kSeamBins; ++b) Add(seam_[b], seam_sums[b] / seam_bin_area, world_density);
    for (int r = 0; r < kRings; ++r) {
      Add(rings_[r], ring_sums[r] / (rank_zero_centres * RingArea(r)), world_density);
    }
  }

  // Signed distance of p to the nearest seam across `axis` (0: the seams x = side k), positive
  // on the higher-ranked side; NaN where that seam is the block's own edge.
  double SignedSeamDistance(Vec2 p, int axis) const {
    const double along = axis == 0 ? p.x : p.y, across = axis == 0 ? p.y : p.x;
    const double seam_number = std::round(along / side_);
    if (seam_number <= 0 || seam_number >= kBlockRegions) return NAN;
    const auto low = static_cast<int64_t>(seam_number) - 1;
    const auto row = static_cast<int64_t>(std::floor(across / side_));
    const RegionKey below = axis == 0 ? RegionKey{low, row} : RegionKey{row, low};
    const RegionKey above = axis == 0 ? RegionKey{low + 1, row} : RegionKey{row, low + 1};
    return (along - side_ * seam_number) * (RegionRank(above) > RegionRank(below) ? 1.0 : -1.0);
  }

  // Distance of p to the centre of the rank-0 region of its 2 x 2 block of regions.
  double DistanceToRankZeroCentre(Vec2 p) const {
    const double period = 2 * side_, half = side_ / 2;
    const double cx = period * std::floor(p.x / period) + half;
    const double cy = period * std::floor(p.y / period) + half;
    return std::hypot(p.x - cx, p.y - cy);
  }

 private:
  static void Add(Bin& bin, double bin_density, double world_density) {
    bin.density.push_back(bin_density);
    bin.excess.push_back(bin_density - world_density);
  }

  double side_;
  int worlds_ = 0;
  double density_sum_ = 0.0;
  std::vector<Bin> seam_ = std::vector<Bin>(kSeamBins), rings_ = std::vector<Bin>(kRings);
};

}  // namespace scallop
