// RegionExclusions (issue 19): the exclusion disks a later layer's region is generated with,
// listed as the engine generates it, against a list written apart from the code under test:
// every point of every earlier layer's regions around the key, layer by layer, regions by rows
// and columns, points in index order, kept when strictly within D of the region's sampled
// rectangle. A list taken on the region's own rectangle instead (a planted fault) is caught.
#include "scallop/plane/region_exclusions.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <span>
#include <vector>

#include "scallop/plane/plane_engine.h"
#include "scallop/plane/region_generator.h"
#include "scallop/plane/world_layers.h"
#include "scallop/random/rng.h"
#include "tests/layer_checks.h"
#include "tests/test_worlds.h"

namespace scallop {
namespace {

// The regions of `world` the engine gives, one by one.
ResolveRegions ByRegion(PlaneEngine& engine) {
  return [&engine](const World& world, const std::vector<RegionKey>& keys) {
    std::vector<RegionHandle> regions;
    for (const RegionKey& key : keys) regions.push_back(*engine.Region(world, key));
    return regions;
  };
}

// Every coordinate and radius by its bits.
std::vector<uint64_t> Bits(std::span<const ExclusionDisk> disks) {
  std::vector<uint64_t> bits;
  for (const ExclusionDisk& disk : disks) {
    bits.push_back(std::bit_cast<uint64_t>(disk.centre.x));
    bits.push_back(std::bit_cast<uint64_t>(disk.centre.y));
    bits.push_back(std::bit_cast<uint64_t>(disk.radius));
  }
  return bits;
}

// The disks of earlier layers' points strictly within D of `around`, from the definition: every
// region of each earlier layer within three of its regions of `around` (its points lie in its
// own rectangle, so a farther region has none within D <= 4 r_max), by rows, then columns.
std::vector<ExclusionDisk> BruteForceDisks(PlaneEngine& engine, const World& world,
                                           const Rect& around) {
  std::vector<ExclusionDisk> disks;
  const EarlierLayers& earlier = *world.earlier_layers();
  for (size_t j = 0; j < earlier.worlds.size(); ++j) {
    const double distance = earlier.distances[j];
    if (!(distance > 0.0)) continue;
    const RegionLayout layout(earlier.worlds[j]);
    const RegionKey low = layout.RegionOf(around.x0, around.y0);
    const RegionKey high = layout.RegionOf(around.x1, around.y1);
    for (int64_t rj = low.j - 3; rj <= high.j + 3; ++rj) {
      for (int64_t ri = low.i - 3; ri <= high.i + 3; ++ri) {
        for (const Vec2& p : (*engine.Region(earlier.worlds[j], {ri, rj}))->points) {
          const double dx = std::max({around.x0 - p.x, 0.0, p.x - around.x1});
          const double dy = std::max({around.y0 - p.y, 0.0, p.y - around.y1});
          if (dx * dx + dy * dy < distance * distance) disks.push_back({p, distance});
        }
      }
    }
  }
  return disks;
}

TEST(LayerExclusionsTest, EachKeyGetsEveryEarlierPointWithinDOfItsSampledRectangle) {
  constexpr uint64_t kSeed = 0xd15c;
  Rng dice(kSeed);
  // The forest (later layers' D 2.81 and 1.32), with noise bushes (a field layer takes the
  // disks too), and a world whose small layer keeps no distance from one earlier layer (D 0:
  // no disks) and 3 from the other.
  WorldSpec overlapping{.seed = 5};
  overlapping.layers = {{.name = "big", .min_distance = 4},
                        {.name = "mid", .min_distance = 2},
                        {.name = "small", .min_distance = 1}};
  overlapping.exclusions = {{.first = "big", .second = "small", .distance = 3},
                            {.first = "mid", .second = "small", .distance = 0}};
  const std::vector<World> worlds = {Forest(3), Forest(4, true), ValidWorld(overlapping)};
  PlaneEngine engine(PlaneEngineOptions{.threads = 1});
  int keys = 0, nonempty = 0, caught = 0;
  for (const World& layered : worlds) {
    const WorldLayers& layers = *layered.layers();
    for (int k = 0; k < layers.count(); ++k) {
      const World& world = layers.world(k);
      if (world.earlier_layers() == nullptr) continue;
      for (int trial = 0; trial < 3; ++trial) {
        // A few keys near a random place, negative indices too.
        std::vector<RegionKey> wanted;
        const RegionKey base{static_cast<int64_t>(dice.Below(40)) - 20,
                             static_cast<int64_t>(dice.Below(40)) - 20};
        for (int n = 1 + static_cast<int>(dice.Below(4)); n > 0; --n) {
          wanted.push_back({base.i + static_cast<int64_t>(dice.Below(3)),
                            base.j + static_cast<int64_t>(dice.Below(3))});
        }
        const RegionExclusions exclusions(world, wanted, ByRegion(engine));
        // Storage left holding another key's disks and more: only the answer counts.
        std::vector<ExclusionDisk> storage(3000, ExclusionDisk{{1e9, 1e9}, 7.0});
        for (const RegionKey& key : wanted) {
          SCOPED_TRACE(::testing::Message() << "seed " << kSeed << ", " << world.Describe()
                                            << ", region " << key.i << "," << key.j);
          const std::span<const ExclusionDisk> got = exclusions.DisksFor(key, storage);
          const std::vector<ExclusionDisk> expected =
              BruteForceDisks(engine, world, SampledRect(world, key));
          ASSERT_EQ(Bits(got), Bits(expected));
          ++keys;
          nonempty += !expected.empty();
          // The planted fault: the disks within D of the region's own rectangle, not of the
          // rectangle its run samples.
          caught += Bits(got) !=
                    Bits(BruteForceDisks(engine, world, RegionLayout(world).RegionRect(key)));
        }
      }
    }
  }
  EXPECT_GE(keys, 3 * 2 * 3) << "every later layer of every world tried";
  EXPECT_EQ(nonempty, keys);
  EXPECT_EQ(caught, keys);
}

}  // namespace
}  // namespace scallop
