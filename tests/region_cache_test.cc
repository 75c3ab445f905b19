// The region cache computes each region once, even when many threads want it
// at the same moment, stays within its byte budget, and its peeks (a server's
// warm answers) see whole regions while other threads generate and evict.
#include "scallop/plane/region_cache.h"

#include <gtest/gtest.h>

#include <atomic>
#include <map>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "scallop/plane/plane_engine.h"
#include "scallop/random/rng.h"
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

// A server answers warm calls from CachedRegions on its network threads while
// its engine generates and evicts for cold calls. Two threads query random
// tiles of a small pool through a cache that holds a few tiles' regions (so
// regions are published and evicted all along) while two others peek at the
// same tiles until the queries are done and each has found five tiles whole:
// every region a peek returns must hold the points a lone engine generates for
// its key. Under ThreadSanitizer (label "threads") this is the test that sees
// PeekAll race with Publish and the eviction; without it, a torn region shows
// as wrong points. Seed printed.
TEST(RegionCacheTest, PeeksWhileOthersGenerateAndEvictSeeWholeRegions) {
  const World world = ValidWorld({.seed = 4242});
  const uint64_t seed = 20261127;
  std::vector<Rect> tiles;
  Rng rng(seed);
  for (int k = 0; k < 6; ++k) {
    const double x = rng.Uniform(-200, 200), y = rng.Uniform(-200, 200);
    tiles.push_back({x, y, x + 40, y + 40});
  }
  std::map<std::pair<int64_t, int64_t>, std::vector<Vec2>> expected;
  PlaneEngine lone(PlaneEngineOptions{.threads = 1});
  for (const Rect& tile : tiles) {
    const StatusOr<std::vector<RegionHandle>> regions = lone.Regions(world, tile);
    ASSERT_TRUE(regions.ok());
    for (const RegionHandle& region : *regions) {
      expected[{region->key.i, region->key.j}] = region->points;
    }
  }

  PlaneEngineOptions options;
  options.threads = 2;
  options.cache_bytes = 1 << 20;  // about 4 tiles' regions with their neighbours: not all 6
  PlaneEngine shared(options);
  std::atomic<int> queries_left{2}, wrong_regions{0};
  std::vector<std::thread> threads;
  for (uint64_t t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      Rng own(HashWords({seed, t}));
      if (t < 2) {
        for (int call = 0; call < 40; ++call) {
          EXPECT_TRUE(shared.Points(world, tiles[own.Below(tiles.size())]).ok());
        }
        --queries_left;
        return;
      }
      // The tiles last queried stay cached, so the loop ends once the queries have.
      for (int found = 0; queries_left > 0 || found < 5;) {
        const std::optional<std::vector<RegionHandle>> regions =
            shared.CachedRegions(world, tiles[own.Below(tiles.size())]);
        if (!regions) continue;
        ++found;
        for (const RegionHandle& region : *regions) {
          wrong_regions += region->points != expected.at({region->key.i, region->key.j});
        }
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  EXPECT_EQ(wrong_regions.load(), 0) << "seed " << seed;
  EXPECT_GT(shared.CacheStats().evictions, 0) << "seed " << seed;
}

// PeekAll against a model of the cache (no eviction: a large budget): a map
// from (world, key) to the region published. Three worlds, two of them equal
// but made apart, so equal worlds must share entries and the third none.
// Random publishes and PeekAlls of random key sets (seed printed).
TEST(RegionCacheTest, PeekAllAnswersAsAModelOfTheCache) {
  const World first = ValidWorld({.seed = 5});
  const World twin = ValidWorld({.seed = 5});  // equal to `first`, another object
  const World other = ValidWorld({.seed = 6});
  const std::vector<const World*> worlds = {&first, &twin, &other};
  // Model keys: the world's class (first and twin are one) and the region.
  std::map<std::pair<int, RegionKey>, RegionHandle> stored;
  for (const uint64_t seed : {1, 2, 3}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    RegionCache cache(int64_t{1} << 30);
    stored.clear();
    Rng rng(seed);
    auto random_key = [&] {
      return RegionKey{static_cast<int64_t>(rng.Below(6)) - 3, static_cast<int64_t>(rng.Below(6))};
    };
    for (int step = 0; step < 2000; ++step) {
      const size_t w = rng.Below(worlds.size());
      const World& world = *worlds[w];
      const int world_class = w == 2 ? 1 : 0;
      if (rng.Below(3) == 0) {
        const RegionKey key = random_key();
        RegionCache::Lookup lookup = cache.Acquire(world, key);
        if (!lookup.must_generate) continue;  // stored already (a hit)
        ASSERT_FALSE(stored.contains({world_class, key}));
        auto region = std::make_shared<const RegionPoints>(
            RegionPoints{key, {{rng.Uniform(), rng.Uniform()}}, 0, {}, {}});
        cache.Publish(world, key, region);
        stored[{world_class, key}] = region;
        continue;
      }
      std::vector<RegionKey> keys(1 + rng.Below(5));
      for (RegionKey& key : keys) key = random_key();
      bool all_stored = true;
      for (const RegionKey& key : keys) all_stored &= stored.contains({world_class, key});
      const int64_t hits_before = cache.Stats().hits;
      std::vector<RegionHandle> regions = {nullptr};  // PeekAll clears it
      ASSERT_EQ(cache.PeekAll(world, keys, regions), all_stored) << "step " << step;
      EXPECT_EQ(cache.Stats().hits - hits_before,
                all_stored ? static_cast<int64_t>(keys.size()) : 0);
      if (!all_stored) {
        EXPECT_TRUE(regions.empty());
        continue;
      }
      ASSERT_EQ(regions.size(), keys.size());
      for (size_t k = 0; k < keys.size(); ++k) {
        EXPECT_EQ(regions[k], stored.at({world_class, keys[k]})) << "step " << step;
      }
    }
    EXPECT_EQ(cache.Stats().misses, static_cast<int64_t>(stored.size()));
  }
}

// PeekAll against a model under eviction: a budget of a few dozen regions,
// keys of two worlds over 8 x 8 regions astride the origin (blocks of the
// directory on both sides of zero), random publishes and PeekAlls. The cache
// holds the only reference to what it stores, so a region is cached exactly
// while the model's weak pointer to it lives: PeekAll must find every key
// so, or fail, and never return an evicted region (a slot left behind).
TEST(RegionCacheTest, PeekAllAnswersAsAModelUnderEviction) {
  const World first = ValidWorld({.seed = 5});
  const World other = ValidWorld({.seed = 6});
  const std::vector<const World*> worlds = {&first, &other};
  auto region_at = [](RegionKey key) {
    return std::make_shared<const RegionPoints>(RegionPoints{key, {{0, 0}}, 0, {}, {}});
  };
  const int64_t one_region =
      static_cast<int64_t>(region_at({0, 0})->Bytes()) + RegionCache::kEntryBookkeepingBytes;
  for (const uint64_t seed : {1, 2, 3}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    RegionCache cache(64 * one_region);
    std::map<std::pair<size_t, RegionKey>, std::weak_ptr<const RegionPoints>> published;
    Rng rng(seed);
    auto random_key = [&] {
      return RegionKey{static_cast<int64_t>(rng.Below(8)) - 4,
                       static_cast<int64_t>(rng.Below(8)) - 4};
    };
    int successes = 0;
    for (int step = 0; step < 5000; ++step) {
      const size_t w = rng.Below(worlds.size());
      if (rng.Below(2) == 0) {
        const RegionKey key = random_key();
        const RegionCache::Lookup lookup = cache.Acquire(*worlds[w], key);
        const bool expired = published[{w, key}].expired();
        ASSERT_EQ(lookup.must_generate, expired) << "step " << step;
        if (lookup.must_generate) {
          RegionHandle region = region_at(key);
          published[{w, key}] = region;
          cache.Publish(*worlds[w], key, std::move(region));
        }
        continue;
      }
      // A small tile, row by row, as GetPoints asks.
      const RegionKey corner = random_key();
      std::vector<RegionKey> keys;
      const int64_t columns = 1 + static_cast<int64_t>(rng.Below(3));
      const int64_t rows = 1 + static_cast<int64_t>(rng.Below(3));
      for (int64_t j = 0; j < rows; ++j) {
        for (int64_t i = 0; i < columns; ++i) keys.push_back({corner.i + i, corner.j + j});
      }
      bool all_cached = true;
      for (const RegionKey& key : keys) {
        const auto it = published.find({w, key});
        all_cached &= it != published.end() && !it->second.expired();
      }
      std::vector<RegionHandle> regions;
      ASSERT_EQ(cache.PeekAll(*worlds[w], keys, regions), all_cached) << "step " << step;
      successes += all_cached ? 1 : 0;
      for (size_t k = 0; k < regions.size(); ++k) {
        EXPECT_EQ(regions[k], published.at({w, keys[k]}).lock()) << "step " << step;
      }
    }
    EXPECT_GT(cache.Stats().evictions, 500);
    EXPECT_GT(successes, 100);
    EXPECT_LE(cache.Stats().bytes, 64 * one_region);
  }
}

// PeekAll neither waits on nor returns a region being generated, and the
// regions it read are the most recently used: a publish over budget evicts
// the others first.
TEST(RegionCacheTest, PeekAllSkipsPendingRegionsAndRefreshesWhatItRead) {
  const World world;
  auto region_at = [](RegionKey key) {
    return std::make_shared<const RegionPoints>(RegionPoints{key, {{0, 0}}, 0, {}, {}});
  };
  const int64_t one_region =
      static_cast<int64_t>(region_at({0, 0})->Bytes()) + RegionCache::kEntryBookkeepingBytes;
  // Room for three, in one block of the directory.
  RegionCache cache(3 * one_region + RegionCache::kBlockBookkeepingBytes);
  const std::vector<RegionKey> keys = {{0, 0}, {1, 0}, {2, 0}};
  for (const RegionKey& key : keys) {
    ASSERT_TRUE(cache.Acquire(world, key).must_generate);
    cache.Publish(world, key, region_at(key));
  }
  std::vector<RegionHandle> regions;
  ASSERT_TRUE(cache.Acquire(world, {3, 0}).must_generate);  // pending now
  EXPECT_FALSE(cache.PeekAll(world, std::vector<RegionKey>{{0, 0}, {3, 0}}, regions));
  // (0, 0) read last: (1, 0), the least recently used, goes when (3, 0) is published.
  ASSERT_TRUE(cache.PeekAll(world, std::vector<RegionKey>{{2, 0}, {0, 0}}, regions));
  cache.Publish(world, {3, 0}, region_at({3, 0}));
  EXPECT_EQ(cache.Stats().evictions, 1);
  EXPECT_TRUE(cache.PeekAll(world, std::vector<RegionKey>{{0, 0}, {2, 0}, {3, 0}}, regions));
  EXPECT_FALSE(cache.PeekAll(world, std::vector<RegionKey>{{1, 0}}, regions));
}

}  // namespace
}  // namespace scallop
