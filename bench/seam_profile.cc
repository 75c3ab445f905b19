// Worlds' density against their regions (docs/quality.md, "The whole profile" under Seams, and
// "Across seams" under Radius fields), as tests/seam_profile.h measures it, over WORLDS worlds:
// A3 worlds of d = 1 (regions 16 d: bins of d / 2, rings of d), or with RATIO noise-field worlds
// over [1, RATIO] at 90% of the slope bound (regions 6 r_max). Each bin is also given as z: the
// mean over the worlds of the bin's density less the world's own, in standard errors of that
// mean. Two more ring profiles say what a seed's core is: rings about the seed itself (the point
// nearest a rank-0 centre), against rings about typical points (9 a world, drawn at random among
// its points at least a region from the block's edge).
//
// Usage: seam_profile [worlds=200] [first seed=0xa3000] [noise field ratio]
#include "tests/seam_profile.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include "scallop/plane/plane_engine.h"
#include "scallop/plane/region_layout.h"
#include "scallop/random/rng.h"

namespace {

using scallop::SeamProfile;
using scallop::Vec2;

// Points (each counting its weight) in rings about each of some centres, summed.
struct RingsAbout {
  std::vector<double> sums = std::vector<double>(SeamProfile::kRings);
  int centres = 0;
  void Add(const std::vector<Vec2>& points, const std::vector<double>& weight,
           const std::vector<Vec2>& about, double width) {
    for (const Vec2& c : about) {
      for (size_t i = 0; i < points.size(); ++i) {
        const double ring = std::hypot(points[i].x - c.x, points[i].y - c.y) / width;
        if (ring < SeamProfile::kRings) sums[static_cast<int>(ring)] += weight[i];
      }
    }
    centres += static_cast<int>(about.size());
  }
  double Density(int r, double width) const {
    return sums[r] / (centres * std::numbers::pi * (2 * r + 1) * width * width);
  }
};

// The point nearest each rank-0 centre of the block: the seed its run grew from.
std::vector<Vec2> Seeds(const std::vector<Vec2>& points, const SeamProfile& profile) {
  std::vector<Vec2> seeds;
  for (int a = 0; a < SeamProfile::kBlockRegions / 2; ++a) {
    for (int b = 0; b < SeamProfile::kBlockRegions / 2; ++b) {
      const Vec2 centre{(2 * a + 0.5) * profile.side(), (2 * b + 0.5) * profile.side()};
      Vec2 nearest = points.front();
      for (const Vec2& p : points) {
        if (std::hypot(p.x - centre.x, p.y - centre.y) <
            std::hypot(nearest.x - centre.x, nearest.y - centre.y)) {
          nearest = p;
        }
      }
      seeds.push_back(nearest);
    }
  }
  return seeds;
}

// Nine points drawn at random among those at least a region from the block's edge.
std::vector<Vec2> TypicalPoints(const std::vector<Vec2>& points, const SeamProfile& profile,
                                scallop::Rng& rng) {
  std::vector<Vec2> typical;
  const double low = profile.side(), high = profile.block() - profile.side();
  while (typical.size() < 9) {
    const Vec2 p = points[rng.Below(points.size())];
    if (p.x >= low && p.x < high && p.y >= low && p.y < high) typical.push_back(p);
  }
  return typical;
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
  // The spacing unit the distances are printed in: d, or r_max for a field.
  const double unit = ratio > 1.0 ? ratio : 1.0;
  const char* unit_name = ratio > 1.0 ? "r_max" : "d";
  scallop::PlaneEngine engine(scallop::PlaneEngineOptions{.threads = 1});
  std::optional<SeamProfile> profile;
  RingsAbout about_seeds, about_typical;
  scallop::Rng rng(first_seed);
  for (int k = 0; k < worlds; ++k) {
    const auto world = scallop::SeamProfileWorld(first_seed + static_cast<uint64_t>(k), ratio);
    if (!profile) profile.emplace(scallop::RegionLayout(*world).side());
    const double block = profile->block();
    const auto points = engine.Points(*world, {0, 0, block, block});
    if (!points.ok()) {
      std::fprintf(stderr, "%s\n", points.status().message().c_str());
      return 1;
    }
    profile->AddWorld(points->positions, world->radius_field());
    std::vector<double> weight;
    for (const Vec2& p : points->positions) {
      const double r = world->radius_field() ? world->radius_field()->Evaluate(p) : 1.0;
      weight.push_back(r * r);
    }
    const double width = profile->RingFrom(1);
    about_seeds.Add(points->positions, weight, Seeds(points->positions, *profile), width);
    about_typical.Add(points->positions, weight, TypicalPoints(points->positions, *profile, rng),
                      width);
  }
  std::printf("%d %s worlds from seed %#llx, regions %g %s, blocks of %d x %d regions: %.4f %s\n",
              worlds, ratio > 1.0 ? "noise-field" : "A3",
              static_cast<unsigned long long>(first_seed), profile->side() / unit, unit_name,
              SeamProfile::kBlockRegions, SeamProfile::kBlockRegions, profile->MeanDensity(),
              ratio > 1.0 ? "points a unit area, each counting R^2" : "points per d^2");
  std::printf("seam (from, %s; density; z):", unit_name);
  for (int b = 0; b < SeamProfile::kSeamBins; ++b) {
    const SeamProfile::Bin& bin = profile->seam()[b];
    std::printf(" %+.2f:%.3f:%+.1f", profile->SeamBinFrom(b) / unit, bin.Density(), bin.Z());
  }
  std::printf("\nrank 0 (ring from, %s; density; z):", unit_name);
  for (int r = 0; r < SeamProfile::kRings; ++r) {
    const SeamProfile::Bin& ring = profile->rings()[r];
    std::printf(" %.2f:%.3f:%+.1f", profile->RingFrom(r) / unit, ring.Density(), ring.Z());
  }
  for (const auto& [name, rings] :
       {std::pair{"the seeds", &about_seeds}, std::pair{"typical points", &about_typical}}) {
    std::printf("\nabout %s (ring from, %s; density):", name, unit_name);
    for (int r = 0; r < SeamProfile::kRings; ++r) {
      std::printf(" %.2f:%.3f", profile->RingFrom(r) / unit,
                  rings->Density(r, profile->RingFrom(1)));
    }
  }
  std::printf("\n");
  return 0;
}
