// Worlds' density against their regions (docs/quality.md, "The whole profile" under Seams,
// "Across seams" under Radius fields and Layered worlds), as tests/seam_profile.h measures it,
// over WORLDS worlds:
// A3 worlds of d = 1 (regions 16 d: bins of d / 2, rings of d), or with RATIO noise-field worlds
// over [1, RATIO] at 90% of the slope bound (regions 6 r_max). Each bin is also given as z: the
// mean over the worlds of the bin's density less the world's own, in standard errors of that
// mean. Two more ring profiles say what a seed's core is: rings about the seed itself (the point
// nearest a rank-0 centre), against rings about typical points (9 a world, drawn at random among
// its points at least a region from the block's edge).
//
// With "forest" instead of a ratio: the forest of docs/quality.md's "Layered worlds" (trees 8,
// bushes 3, rocks 1.5), a profile for each layer, in its own regions and d; with "a1:DENSITY" or
// "a2:DENSITY", A1 or A2 worlds of d = 1 at that density.
//
// Usage: seam_profile [worlds=200] [first seed=0xa3000] [ratio | forest | a1:DENSITY | a2:DENSITY]
#include "tests/seam_profile.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "scallop/plane/plane_engine.h"
#include "scallop/plane/region_layout.h"
#include "scallop/plane/world_layers.h"
#include "scallop/random/rng.h"

namespace {

using scallop::SeamProfile;
using scallop::Vec2;

// Points (each counting its weight) in the profile's rings about each of some centres, summed.
struct RingsAbout {
  std::vector<double> sums = std::vector<double>(SeamProfile::kRings);
  int centres = 0;
  void Add(const std::vector<Vec2>& points, const std::vector<double>& weight,
           const std::vector<Vec2>& about, const SeamProfile& profile) {
    for (const Vec2& c : about) {
      for (size_t i = 0; i < points.size(); ++i) {
        const double ring = std::hypot(points[i].x - c.x, points[i].y - c.y) / profile.RingFrom(1);
        if (ring < SeamProfile::kRings) sums[static_cast<int>(ring)] += weight[i];
      }
    }
    centres += static_cast<int>(about.size());
  }
  double Density(int r, const SeamProfile& profile) const {
    return sums[r] / (centres * profile.RingArea(r));
  }
};

// The point nearest each rank-0 centre of the block: the seed its run grew from (in a later layer,
// unless the seed fell in an earlier layer's disk and was dropped).
std::vector<Vec2> Seeds(const std::vector<Vec2>& points, const SeamProfile& profile) {
  std::vector<Vec2> seeds;
  for (const Vec2& centre : profile.RankZeroCentres()) {
    Vec2 nearest = points.front();
    for (const Vec2& p : points) {
      if (std::hypot(p.x - centre.x, p.y - centre.y) <
          std::hypot(nearest.x - centre.x, nearest.y - centre.y)) {
        nearest = p;
      }
    }
    seeds.push_back(nearest);
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

struct Measured {
  std::optional<SeamProfile> profile;
  RingsAbout about_seeds, about_typical;
};

// One profile over the worlds `make_world` gives for seeds first_seed, first_seed + 1, ...: of each
// world, or with `layer` >= 0 of that layer of each (layered) world.
template <typename MakeWorld>
bool Measure(scallop::PlaneEngine& engine, int worlds, uint64_t first_seed, MakeWorld make_world,
             int layer, Measured& measured) {
  scallop::Rng rng(first_seed);
  for (int k = 0; k < worlds; ++k) {
    const scallop::World world = make_world(first_seed + static_cast<uint64_t>(k));
    const scallop::World& own = layer >= 0 ? world.layers()->world(layer) : world;
    if (!measured.profile) measured.profile.emplace(scallop::RegionLayout(own).side());
    const SeamProfile& profile = *measured.profile;
    const double block = profile.block();
    const auto points =
        engine.Points(world, {0, 0, block, block},
                      layer >= 0 ? scallop::LayerMask{1u} << layer : scallop::kAllLayers);
    if (!points.ok()) {
      std::fprintf(stderr, "%s\n", points.status().message().c_str());
      return false;
    }
    measured.profile->AddWorld(points->positions, own);
    std::vector<double> weight;
    for (const Vec2& p : points->positions) weight.push_back(SeamProfile::Weight(own, p));
    measured.about_seeds.Add(points->positions, weight, Seeds(points->positions, profile), profile);
    measured.about_typical.Add(points->positions, weight,
                               TypicalPoints(points->positions, profile, rng), profile);
  }
  return true;
}

// Distances in `unit` (d or r_max, named `unit_name`), densities in points per `per`: a point
// counts its spacing squared (d^2 or R^2).
void Print(const Measured& measured, const char* what, int worlds, uint64_t first_seed, double unit,
           const char* unit_name, const char* per) {
  const SeamProfile& profile = *measured.profile;
  std::printf(
      "%d %s from seed %#llx, regions %g %s, blocks of %d x %d regions: %.4f points per %s\n",
      worlds, what, static_cast<unsigned long long>(first_seed), profile.side() / unit, unit_name,
      SeamProfile::kBlockRegions, SeamProfile::kBlockRegions, profile.MeanDensity(), per);
  std::printf("seam (from, %s; density; z):", unit_name);
  for (int b = 0; b < SeamProfile::kSeamBins; ++b) {
    const SeamProfile::Bin& bin = profile.seam()[b];
    std::printf(" %+.2f:%.3f:%+.1f", profile.SeamBinFrom(b) / unit, bin.Density(), bin.Z());
  }
  std::printf("\nrank 0 (ring from, %s; density; z):", unit_name);
  for (int r = 0; r < SeamProfile::kRings; ++r) {
    const SeamProfile::Bin& ring = profile.rings()[r];
    std::printf(" %.2f:%.3f:%+.1f", profile.RingFrom(r) / unit, ring.Density(), ring.Z());
  }
  for (const auto& [name, rings] : {std::pair{"the seeds", &measured.about_seeds},
                                    std::pair{"typical points", &measured.about_typical}}) {
    std::printf("\nabout %s (ring from, %s; density):", name, unit_name);
    for (int r = 0; r < SeamProfile::kRings; ++r) {
      std::printf(" %.2f:%.3f", profile.RingFrom(r) / unit, rings->Density(r, profile));
    }
  }
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  const int worlds = argc > 1 ? std::atoi(argv[1]) : 200;
  const uint64_t first_seed = argc > 2 ? std::strtoull(argv[2], nullptr, 0) : 0xa3000;
  const std::string_view kind = argc > 3 ? argv[3] : "";
  const bool forest = kind == "forest";
  // "a1:1.5", "a2:1.5": A1 or A2 at that density.
  const bool a1 = kind.starts_with("a1:"), a2 = kind.starts_with("a2:");
  const double density = a1 || a2 ? std::atof(argv[3] + 3) : 2.0;
  const double ratio = argc > 3 && !forest && !a1 && !a2 ? std::atof(argv[3]) : 1.0;
  if (worlds < 2 || !(ratio >= 1.0) || !(density > 1.0 && density <= 2.0)) {
    std::fprintf(stderr,
                 "usage: %s [worlds >= 2] [first seed] [noise field ratio > 1 | forest | "
                 "a1:DENSITY | a2:DENSITY]\n",
                 argv[0]);
    return 2;
  }
  scallop::PlaneEngine engine(scallop::PlaneEngineOptions{.threads = 1});
  if (forest) {
    const scallop::World first = *scallop::SeamProfileForest(first_seed);
    for (int layer = 0; layer < first.layers()->count(); ++layer) {
      Measured measured;
      const auto make_world = [](uint64_t seed) { return *scallop::SeamProfileForest(seed); };
      if (!Measure(engine, worlds, first_seed, make_world, layer, measured)) return 1;
      const std::string what = "forests' " + first.layers()->name(layer);
      Print(measured, what.c_str(), worlds, first_seed, first.layers()->world(layer).min_distance(),
            "d", "d^2");
    }
    return 0;
  }
  if (a1 || a2) {
    Measured measured;
    const auto algorithm = a1 ? scallop::WorldAlgorithm::kA1 : scallop::WorldAlgorithm::kA2;
    const auto make_world = [algorithm, density](uint64_t seed) {
      return *scallop::SeamProfileWorld(seed, algorithm, density);
    };
    if (!Measure(engine, worlds, first_seed, make_world, -1, measured)) return 1;
    const std::string what = std::string(a1 ? "A1" : "A2") + " worlds of density " + (argv[3] + 3);
    Print(measured, what.c_str(), worlds, first_seed, 1.0, "d", "d^2");
    return 0;
  }
  Measured measured;
  const auto make_world = [ratio](uint64_t seed) {
    return *scallop::SeamProfileWorld(seed, ratio);
  };
  if (!Measure(engine, worlds, first_seed, make_world, -1, measured)) return 1;
  Print(measured, ratio > 1.0 ? "noise-field worlds" : "A3 worlds", worlds, first_seed,
        ratio > 1.0 ? ratio : 1.0, ratio > 1.0 ? "r_max" : "d", ratio > 1.0 ? "R^2" : "d^2");
  return 0;
}
