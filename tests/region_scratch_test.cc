// A region's run in a RegionScratch that earlier runs left behind (other
// worlds, algorithms, d, regions, layers) gives, bit for bit, the region a run
// without one gives, and the engine's: the plane engine's threads each reuse
// one scratch for region after region.
#include "scallop/plane/region_scratch.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <span>
#include <vector>

#include "scallop/plane/plane_engine.h"
#include "scallop/plane/region_exclusions.h"
#include "scallop/plane/region_generator.h"
#include "scallop/plane/world_layers.h"
#include "scallop/random/rng.h"
#include "tests/field_test_fields.h"
#include "tests/layer_checks.h"
#include "tests/test_worlds.h"

namespace scallop {
namespace {

// Every field of a region, coordinates by their bits.
std::vector<uint64_t> Bits(const RegionPoints& region) {
  std::vector<uint64_t> bits = {static_cast<uint64_t>(region.key.i),
                                static_cast<uint64_t>(region.key.j),
                                region.adopted,
                                region.points.size(),
                                region.spill.size(),
                                region.unprocessed.size()};
  for (const std::vector<Vec2>* list : {&region.points, &region.spill}) {
    for (const Vec2& p : *list) {
      bits.push_back(std::bit_cast<uint64_t>(p.x));
      bits.push_back(std::bit_cast<uint64_t>(p.y));
    }
  }
  for (const bool flag : region.unprocessed) bits.push_back(flag);
  return bits;
}

TEST(RegionScratchTest, AUsedScratchGivesTheRegionOfNone) {
  constexpr uint64_t kSeed = 0x5c7a;
  Rng dice(kSeed);
  PlaneEngine engine(PlaneEngineOptions{.threads = 1});
  RegionScratch scratch;  // every run below, in a random order of worlds and regions
  WorldSpec field_spec{.seed = dice.NextBits()};
  field_spec.radius_field = field_test::NoiseField(dice.NextBits(), 0.5, 3.0).spec();
  // A3 gives flags, A1 and A2 none: a scratch must not carry A3's to them. A later layer's A3
  // keeps its exclusion disks' grid and tables in the scratch (BoundaryScratch::exclusions),
  // and the engine their list (RegionScratch::exclusions): a noise field's layer takes the disks
  // as masks.
  const World forest = Forest(dice.NextBits()), noise_forest = Forest(dice.NextBits(), true);
  const std::vector<World> worlds = {DiceWorld(dice, WorldAlgorithm::kA3, 1.0),
                                     DiceWorld(dice, WorldAlgorithm::kA1, 0.37),
                                     DiceWorld(dice, WorldAlgorithm::kA3, 3.1),
                                     DiceWorld(dice, WorldAlgorithm::kA2, 1.0),
                                     ValidWorld(field_spec),
                                     forest.layers()->world(1),
                                     forest.layers()->world(2),
                                     noise_forest.layers()->world(1),
                                     noise_forest.layers()->world(2)};
  // A later layer's disks, listed as the engine lists them.
  const auto disks_for = [&](const World& world, RegionKey key,
                             std::vector<ExclusionDisk>& storage) {
    if (world.earlier_layers() == nullptr) return std::span<const ExclusionDisk>{};
    const RegionExclusions exclusions(
        world, {key}, [&engine](const World& layer, const std::vector<RegionKey>& keys) {
          std::vector<RegionHandle> regions;
          for (const RegionKey& k : keys) regions.push_back(*engine.Region(layer, k));
          return regions;
        });
    return exclusions.DisksFor(key, storage);
  };
  int layered = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const World& world = worlds[dice.Below(worlds.size())];
    const RegionKey key{static_cast<int64_t>(dice.Below(9)) - 4,
                        static_cast<int64_t>(dice.Below(9)) - 4};
    SCOPED_TRACE(::testing::Message() << "seed " << kSeed << ", trial " << trial << ", "
                                      << world.Describe() << ", region " << key.i << "," << key.j);
    std::vector<RegionHandle> held;
    std::vector<const RegionPoints*> neighbours;
    for (const RegionKey& n : LowerRankedNeighbours(key)) {
      held.push_back(*engine.Region(world, n));
      neighbours.push_back(held.back().get());
    }
    std::vector<ExclusionDisk> storage;
    const std::span<const ExclusionDisk> disks = disks_for(world, key, storage);
    layered += !disks.empty();
    const std::vector<uint64_t> without = Bits(GenerateRegion(world, key, neighbours, disks));
    // 18 points or more: a noise layer's region of 6 r_max holds few.
    ASSERT_GT(without.size(), 40u);
    EXPECT_EQ(Bits(GenerateRegion(world, key, neighbours, disks, &scratch)), without);
    EXPECT_EQ(Bits(**engine.Region(world, key)), without);
  }
  EXPECT_GT(layered, 15);
}

}  // namespace
}  // namespace scallop
