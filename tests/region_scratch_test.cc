// A region's run in a RegionScratch that earlier runs left behind (other
// worlds, algorithms, d, regions) gives, bit for bit, the region a run
// without one gives, and the engine's: the plane engine's threads each reuse
// one scratch for region after region.
#include "scallop/plane/region_scratch.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <vector>

#include "scallop/plane/plane_engine.h"
#include "scallop/plane/region_generator.h"
#include "scallop/random/rng.h"
#include "tests/field_test_fields.h"
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
  WorldSpec field_spec{.seed = dice.NextBits()};
  field_spec.radius_field = field_test::NoiseField(dice.NextBits(), 0.5, 3.0).spec();
  // A3 gives flags, A1 and A2 none: a scratch must not carry A3's to them.
  const std::vector<World> worlds = {
      DiceWorld(dice, WorldAlgorithm::kA3, 1.0), DiceWorld(dice, WorldAlgorithm::kA1, 0.37),
      DiceWorld(dice, WorldAlgorithm::kA3, 3.1), DiceWorld(dice, WorldAlgorithm::kA2, 1.0),
      ValidWorld(field_spec)};
  PlaneEngine engine(PlaneEngineOptions{.threads = 1});
  RegionScratch scratch;  // every run below, in a random order of worlds and regions
  for (int trial = 0; trial < 40; ++trial) {
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
    const std::vector<uint64_t> without = Bits(GenerateRegion(world, key, neighbours));
    ASSERT_GT(without.size(), 100u);
    EXPECT_EQ(Bits(GenerateRegion(world, key, neighbours, {}, &scratch)), without);
    EXPECT_EQ(Bits(**engine.Region(world, key)), without);
  }
}

}  // namespace
}  // namespace scallop
