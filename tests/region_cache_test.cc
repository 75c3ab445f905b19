// The region cache computes each region once, even when many threads want it
// at the same moment, and stays within its byte budget.
#include "scallop/plane/region_cache.h"

#include <gtest/gtest.h>

#include <thread>
#include <vector>

#include "scallop/plane/plane_engine.h"
#include "tests/test_worlds.h"

namespace scallop {
namespace {

TEST(RegionCacheTest, ExactlyOneCallerGeneratesAKey) {
  RegionCache cache(int64_t{1} << 20);
  const World world;
  const RegionKey key{3, -4};
  RegionCache::Lookup first = cache.Acquire(world, key);
  RegionCache::Lookup second = cache.Acquire(world, key);
  ASSERT_TRUE(first.must_generate);
  ASSERT_FALSE(second.must_generate);
  ASSERT_TRUE(second.pending.valid());
  auto region = std::make_shared<const RegionPoints>(RegionPoints{key, {{1, 2}}, 0, {}, {}});
  cache.Publish(world, key, region);
  EXPECT_EQ(second.pending.get(), region);  // the waiter gets the publisher's region
  EXPECT_EQ(cache.Acquire(world, key).ready, region);
  EXPECT_EQ(cache.Stats().misses, 1);
  EXPECT_EQ(cache.Stats().hits, 2);
}

// Eight threads ask for the same cold rectangle at once. Every region of its
// closure must be generated exactly once: as many misses as a lone query
// needs. A cache that let two callers generate one key would count more.
TEST(RegionCacheTest, ConcurrentQueriesGenerateEachRegionOnce) {
  for (WorldAlgorithm algorithm : {WorldAlgorithm::kA3, WorldAlgorithm::kA1}) {
    const World world = ValidWorld({.seed = 99, .algorithm = algorithm});
    const Rect rect{-70, -50, 90, 60};

    PlaneEngineOptions lone_options;
    lone_options.threads = 1;
    PlaneEngine lone(lone_options);
    ASSERT_TRUE(lone.Points(world, rect).ok());
    const int64_t regions_needed = lone.CacheStats().misses;
    ASSERT_GT(regions_needed, 50);

    PlaneEngineOptions shared_options;
    shared_options.threads = 2;
    PlaneEngine shared(shared_options);
    std::vector<std::thread> callers;
    std::vector<size_t> counts(8);
    for (size_t t = 0; t < counts.size(); ++t) {
      callers.emplace_back([&, t] { counts[t] = shared.Points(world, rect)->positions.size(); });
    }
    for (std::thread& caller : callers) caller.join();
    const RegionCacheStats stats = shared.CacheStats();
    EXPECT_EQ(stats.misses, regions_needed) << WorldAlgorithmName(algorithm);
    EXPECT_EQ(stats.regions, regions_needed);
    for (size_t count : counts) EXPECT_EQ(count, counts[0]);
  }
}

TEST(RegionCacheTest, StaysWithinItsByteBudget) {
  PlaneEngineOptions options;
  options.cache_bytes = 64 << 10;
  PlaneEngine engine(options);
  const World world;
  for (int k = 0; k < 20; ++k) {
    const double x = 100.0 * k;
    ASSERT_TRUE(engine.Points(world, {x, 0, x + 60, 60}).ok());
    EXPECT_LE(engine.CacheStats().bytes, options.cache_bytes);
  }
  EXPECT_GT(engine.CacheStats().evictions, 0);
}

}  // namespace
}  // namespace scallop
