// Determinism of the infinite plane: a rectangle's points and ids, bit for bit,
// do not depend on how it is tiled, the order of queries, the cache state
// (cold, warm, evicting), the generator thread count or concurrent callers.
// Also the point-id bit layout: round trips, uniqueness, and decoding.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "scallop/plane/plane_engine.h"
#include "scallop/plane/point_id.h"
#include "scallop/plane/region_layout.h"
#include "scallop/random/rng.h"
#include "tests/test_worlds.h"

namespace scallop {
namespace {

constexpr WorldAlgorithm kPlaneAlgorithms[] = {WorldAlgorithm::kA1, WorldAlgorithm::kA2,
                                               WorldAlgorithm::kA3};

// One point as the tests compare it: the id and the coordinates' bit patterns,
// so -0.0 against 0.0 or a last-bit difference counts as a difference.
struct BitPoint {
  uint64_t id;
  uint64_t x;
  uint64_t y;
  friend auto operator<=>(const BitPoint&, const BitPoint&) = default;
};

std::vector<BitPoint> InQueryOrder(const PlanePoints& points) {
  std::vector<BitPoint> out;
  for (size_t k = 0; k < points.positions.size(); ++k) {
    out.push_back({points.ids[k], std::bit_cast<uint64_t>(points.positions[k].x),
                   std::bit_cast<uint64_t>(points.positions[k].y)});
  }
  return out;
}

std::vector<BitPoint> SortedById(const PlanePoints& points) {
  std::vector<BitPoint> out = InQueryOrder(points);
  std::sort(out.begin(), out.end());
  return out;
}

// Equality that reports the first difference instead of printing thousands of
// points.
::testing::AssertionResult SameBits(const std::vector<BitPoint>& expected,
                                    const std::vector<BitPoint>& actual) {
  for (size_t k = 0; k < std::min(expected.size(), actual.size()); ++k) {
    if (expected[k] != actual[k]) {
      return ::testing::AssertionFailure()
             << "first difference at " << k << " of " << expected.size() << "/" << actual.size()
             << ": id " << expected[k].id << " (" << std::bit_cast<double>(expected[k].x) << ", "
             << std::bit_cast<double>(expected[k].y) << ") vs id " << actual[k].id << " ("
             << std::bit_cast<double>(actual[k].x) << ", " << std::bit_cast<double>(actual[k].y)
             << ")";
    }
  }
  if (expected.size() != actual.size()) {
    return ::testing::AssertionFailure()
           << "sizes differ: " << expected.size() << " vs " << actual.size();
  }
  return ::testing::AssertionSuccess();
}

std::string Describe(const Rect& r) {
  std::ostringstream out;
  out.precision(17);
  out << "[" << r.x0 << ", " << r.x1 << ") x [" << r.y0 << ", " << r.y1 << ")";
  return out.str();
}

PlanePoints MustPoints(PlaneEngine& engine, const World& world, const Rect& rect) {
  StatusOr<PlanePoints> points = engine.Points(world, rect);
  EXPECT_TRUE(points.ok()) << points.status().message() << " for " << Describe(rect);
  return points.ok() ? std::move(*points) : PlanePoints{};
}

// Worlds for one algorithm: d = 1, and non-integer d (0.37, 3.1) whose region
// edges 16 k d are rounded doubles, so seams fall between representable
// values in the way a real deployment's would.
std::vector<World> TestWorlds(WorldAlgorithm algorithm, uint64_t dice_seed) {
  Rng dice(dice_seed);
  std::vector<World> worlds;
  for (double d : {1.0, 0.37, 3.1}) {
    const World world = DiceWorld(dice, algorithm, d);
    worlds.push_back(world);
  }
  return worlds;
}

// A rectangle of w x h with w, h in [min_side, max_side) d. Half the time it
// sits across a region corner (so it straddles two seams), otherwise anywhere
// within 2000 d of the origin, negative coordinates included.
Rect RandomRect(Rng& rng, double d, double min_side, double max_side) {
  const double w = d * rng.Uniform(min_side, max_side), h = d * rng.Uniform(min_side, max_side);
  const RegionLayout layout(d);
  double x0, y0;
  if (rng.Below(2) == 0) {
    const Rect corner = layout.RegionRect(
        {static_cast<int64_t>(rng.Below(200)) - 100, static_cast<int64_t>(rng.Below(200)) - 100});
    x0 = corner.x0 - w * rng.Uniform();
    y0 = corner.y0 - h * rng.Uniform();
  } else {
    x0 = d * rng.Uniform(-2000, 2000);
    y0 = d * rng.Uniform(-2000, 2000);
  }
  return {x0, y0, x0 + w, y0 + h};
}

// Cut positions of [lo, hi), both ends included, strictly increasing: a few
// random cuts, a cut exactly on every region edge inside (where a tile edge
// coincides with the seam the engine computes, and half-open ownership must
// hand each point to exactly one side), and slivers one ulp and 1e-9 d wide.
std::vector<double> RandomCuts(Rng& rng, double lo, double hi, const RegionLayout& layout,
                               bool x_axis, double d, int& seam_cuts) {
  std::vector<double> cuts = {lo, hi};
  const int random_cuts = static_cast<int>(rng.Below(4));
  for (int n = 0; n < random_cuts; ++n) cuts.push_back(rng.Uniform(lo, hi));
  const int64_t first = layout.IndexOf(lo), last = layout.IndexOf(hi);
  for (int64_t k = first; k <= last + 1; ++k) {
    const Rect region = layout.RegionRect(x_axis ? RegionKey{k, 0} : RegionKey{0, k});
    const double edge = x_axis ? region.x0 : region.y0;
    if (lo < edge && edge < hi) {
      cuts.push_back(edge);
      ++seam_cuts;
    }
  }
  // Any cut but hi (which sits at index 1).
  size_t pick = rng.Below(cuts.size() - 1);
  if (pick >= 1) ++pick;
  const double base = cuts[pick];
  cuts.push_back(std::nextafter(base, hi));
  if (base + 1e-9 * d < hi) cuts.push_back(base + 1e-9 * d);
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  return cuts;
}

// Tiles of `rect` on a random grid of cuts, in a random order; counts the
// cuts that lie on region edges.
std::vector<Rect> RandomTiling(Rng& rng, const Rect& rect, double d, int& seam_cuts) {
  const RegionLayout layout(d);
  const std::vector<double> xs = RandomCuts(rng, rect.x0, rect.x1, layout, true, d, seam_cuts);
  const std::vector<double> ys = RandomCuts(rng, rect.y0, rect.y1, layout, false, d, seam_cuts);
  std::vector<Rect> tiles;
  for (size_t a = 0; a + 1 < xs.size(); ++a) {
    for (size_t b = 0; b + 1 < ys.size(); ++b) {
      tiles.push_back({xs[a], ys[b], xs[a + 1], ys[b + 1]});
    }
  }
  for (size_t k = tiles.size(); k > 1; --k) std::swap(tiles[k - 1], tiles[rng.Below(k)]);
  return tiles;
}

// Queries every tile (checking Count and containment on the way) and returns
// the union, sorted by id.
std::vector<BitPoint> UnionOfTiles(PlaneEngine& engine, const World& world,
                                   const std::vector<Rect>& tiles) {
  std::vector<BitPoint> all;
  for (const Rect& tile : tiles) {
    const PlanePoints points = MustPoints(engine, world, tile);
    for (const Vec2& p : points.positions) {
      EXPECT_TRUE(tile.Contains(p)) << p.x << "," << p.y << " outside " << Describe(tile);
    }
    StatusOr<int64_t> count = engine.Count(world, tile);
    EXPECT_TRUE(count.ok() && *count == static_cast<int64_t>(points.positions.size()))
        << "Count disagrees with Points on " << Describe(tile);
    const std::vector<BitPoint> bits = InQueryOrder(points);
    all.insert(all.end(), bits.begin(), bits.end());
  }
  std::sort(all.begin(), all.end());
  return all;
}

PlaneEngineOptions EngineOptions(int threads, int64_t cache_bytes) {
  PlaneEngineOptions options;
  options.threads = threads;
  options.cache_bytes = cache_bytes;
  return options;
}

// About 6 regions' worth: every query of more than a few regions evicts
// regions it still depends on, so they are regenerated from scratch.
constexpr int64_t kTinyCacheBytes = 24 << 10;

class PlaneDeterminismTest : public ::testing::TestWithParam<WorldAlgorithm> {};

TEST_P(PlaneDeterminismTest, TilingOrderCacheAndThreadsGiveTheSameBits) {
  const uint64_t seed = HashWords({0x7e57, static_cast<uint64_t>(GetParam())});
  Rng rng(seed);
  // Both persist across trials and worlds, so they carry an arbitrary history.
  PlaneEngine history(EngineOptions(2, int64_t{256} << 20));
  PlaneEngine tiny(EngineOptions(3, kTinyCacheBytes));
  int trials = 0, seam_cuts = 0;
  for (const World& world : TestWorlds(GetParam(), rng.NextBits())) {
    for (int trial = 0; trial < 3; ++trial, ++trials) {
      const Rect rect = RandomRect(rng, world.min_distance(), 6.0, 56.0);
      const uint64_t tiling_seed = rng.NextBits();
      SCOPED_TRACE(::testing::Message()
                   << "test seed " << seed << ", " << world.Describe() << ", rect "
                   << Describe(rect) << ", tiling seed " << tiling_seed);
      PlaneEngine cold(EngineOptions(2, int64_t{256} << 20));
      const PlanePoints reference = MustPoints(cold, world, rect);
      const std::vector<BitPoint> expected = SortedById(reference);
      const std::vector<BitPoint> expected_order = InQueryOrder(reference);
      ASSERT_GT(expected.size(), 10u);
      for (size_t k = 1; k < expected.size(); ++k) {
        ASSERT_NE(expected[k - 1].id, expected[k].id) << "ids must be unique within a query";
      }
      StatusOr<int64_t> count = cold.Count(world, rect);
      ASSERT_TRUE(count.ok()) << count.status().message();
      EXPECT_EQ(*count, static_cast<int64_t>(expected.size()));

      // The same engine, now warm, tiled in a random order, then whole again.
      Rng tiling_rng(tiling_seed);
      const std::vector<Rect> tiles =
          RandomTiling(tiling_rng, rect, world.min_distance(), seam_cuts);
      EXPECT_TRUE(SameBits(expected, UnionOfTiles(cold, world, tiles))) << "warm, tiled";
      EXPECT_TRUE(SameBits(expected_order, InQueryOrder(MustPoints(cold, world, rect))))
          << "warm, whole";

      // Another tiling, in another order, on an engine that keeps evicting.
      const std::vector<Rect> other_tiles =
          RandomTiling(tiling_rng, rect, world.min_distance(), seam_cuts);
      EXPECT_TRUE(SameBits(expected, UnionOfTiles(tiny, world, other_tiles))) << "tiny cache";
      EXPECT_TRUE(SameBits(expected_order, InQueryOrder(MustPoints(tiny, world, rect))))
          << "tiny cache, whole";

      EXPECT_TRUE(SameBits(expected_order, InQueryOrder(MustPoints(history, world, rect))))
          << "engine with history";
      for (int threads : {1, 3}) {
        PlaneEngine fresh(EngineOptions(threads, int64_t{256} << 20));
        EXPECT_TRUE(SameBits(expected_order, InQueryOrder(MustPoints(fresh, world, rect))))
            << threads << " threads";
      }
      if (HasFailure()) return;
    }
  }
  EXPECT_EQ(trials, 9);
  // Tile edges on region seams are the cases most likely to lose or repeat a
  // point; make sure the random tilings had plenty.
  EXPECT_GT(seam_cuts, 20);
  // The tiny engine must really have evicted, or it tested nothing new.
  EXPECT_GT(tiny.CacheStats().evictions, 100);
}

TEST_P(PlaneDeterminismTest, RegionEqualsThePointsOfItsRectangle) {
  const uint64_t seed = HashWords({0x2e610, static_cast<uint64_t>(GetParam())});
  Rng rng(seed);
  PlaneEngine engine(EngineOptions(2, int64_t{256} << 20));
  for (const World& world : TestWorlds(GetParam(), rng.NextBits())) {
    const RegionLayout layout(world.min_distance());
    for (int trial = 0; trial < 4; ++trial) {
      const RegionKey key{static_cast<int64_t>(rng.Below(400)) - 200,
                          static_cast<int64_t>(rng.Below(400)) - 200};
      SCOPED_TRACE(::testing::Message() << "test seed " << seed << ", " << world.Describe()
                                        << ", region " << key.i << "," << key.j);
      // Region first on half the trials, the rectangle first on the others,
      // so each path sees both a cold and a warm cache.
      const bool region_first = trial % 2 == 0;
      PlanePoints from_rect;
      if (!region_first) from_rect = MustPoints(engine, world, layout.RegionRect(key));
      StatusOr<RegionHandle> region = engine.Region(world, key);
      ASSERT_TRUE(region.ok()) << region.status().message();
      if (region_first) from_rect = MustPoints(engine, world, layout.RegionRect(key));
      const RegionPoints& points = **region;
      EXPECT_EQ(points.key, key);
      PlanePoints expected;
      for (size_t k = 0; k < points.points.size(); ++k) {
        EXPECT_TRUE(layout.RegionRect(key).Contains(points.points[k]));
        expected.positions.push_back(points.points[k]);
        expected.ids.push_back(EncodePointId(key, static_cast<uint32_t>(k)));
      }
      ASSERT_GT(expected.positions.size(), 50u);
      EXPECT_TRUE(SameBits(InQueryOrder(expected), InQueryOrder(from_rect)));
    }
  }
}

// Several std::threads share one engine, each asking the same queries in its
// own order; every answer must equal a sequential engine's. Run on a large
// cache (threads wait on each other's in-flight regions) and on a tiny one
// (regions are evicted and regenerated while other threads need them).
TEST_P(PlaneDeterminismTest, ConcurrentCallersGetSequentialResults) {
  const uint64_t seed = HashWords({0xc0c0, static_cast<uint64_t>(GetParam())});
  SCOPED_TRACE(::testing::Message() << "test seed " << seed);
  Rng rng(seed);
  struct Query {
    World world;
    Rect rect;
  };
  std::vector<Query> queries;
  for (const World& world : TestWorlds(GetParam(), rng.NextBits())) {
    for (int n = 0; n < 3; ++n) {
      // Small offsets, so queries overlap and share regions.
      const double d = world.min_distance();
      const double x0 = d * rng.Uniform(-40, 40), y0 = d * rng.Uniform(-40, 40);
      queries.push_back(
          {world, {x0, y0, x0 + d * rng.Uniform(4, 40), y0 + d * rng.Uniform(4, 40)}});
    }
  }
  PlaneEngine sequential(EngineOptions(1, int64_t{256} << 20));
  std::vector<std::vector<BitPoint>> expected;
  for (const Query& q : queries)
    expected.push_back(InQueryOrder(MustPoints(sequential, q.world, q.rect)));

  constexpr int kCallers = 4;
  for (int64_t cache_bytes : {int64_t{256} << 20, kTinyCacheBytes}) {
    SCOPED_TRACE(::testing::Message() << "cache bytes " << cache_bytes);
    PlaneEngine shared(EngineOptions(2, cache_bytes));
    std::vector<std::vector<std::vector<BitPoint>>> got(
        kCallers, std::vector<std::vector<BitPoint>>(queries.size()));
    std::vector<int> failures(kCallers, 0);
    std::vector<std::thread> callers;
    for (int c = 0; c < kCallers; ++c) {
      callers.emplace_back([&, c] {
        // Caller c starts at a different query and strides differently.
        const size_t n = queries.size();
        for (size_t step = 0; step < n; ++step) {
          const size_t q = (c * 5 + step * (c % 2 == 0 ? 1 : n - 1)) % n;
          StatusOr<PlanePoints> points = shared.Points(queries[q].world, queries[q].rect);
          if (!points.ok()) {
            ++failures[c];
            continue;
          }
          got[c][q] = InQueryOrder(*points);
        }
      });
    }
    for (std::thread& t : callers) t.join();
    for (int c = 0; c < kCallers; ++c) {
      EXPECT_EQ(failures[c], 0);
      for (size_t q = 0; q < queries.size(); ++q) {
        EXPECT_TRUE(SameBits(expected[q], got[c][q]))
            << "caller " << c << ", " << queries[q].world.Describe() << ", rect "
            << Describe(queries[q].rect);
      }
    }
  }
}

// Every id of a query is unique, decodes (with the query's own corner region
// as the reference) to the region that owns the point, and indexes that
// region's point list at exactly this point.
TEST_P(PlaneDeterminismTest, IdsDecodeToTheOwningRegion) {
  const uint64_t seed = HashWords({0x1d5, static_cast<uint64_t>(GetParam())});
  Rng rng(seed);
  PlaneEngine engine(EngineOptions(2, int64_t{256} << 20));
  for (const World& world : TestWorlds(GetParam(), rng.NextBits())) {
    const RegionLayout layout(world.min_distance());
    for (int trial = 0; trial < 3; ++trial) {
      const Rect rect = RandomRect(rng, world.min_distance(), 10.0, 50.0);
      SCOPED_TRACE(::testing::Message() << "test seed " << seed << ", " << world.Describe()
                                        << ", rect " << Describe(rect));
      const PlanePoints points = MustPoints(engine, world, rect);
      const RegionKey reference = layout.RegionOf(rect.x0, rect.y0);
      std::vector<uint64_t> ids = points.ids;
      std::sort(ids.begin(), ids.end());
      EXPECT_EQ(std::adjacent_find(ids.begin(), ids.end()), ids.end()) << "duplicate id";
      std::map<RegionKey, RegionHandle> regions;
      for (size_t k = 0; k < points.ids.size(); ++k) {
        const Vec2 p = points.positions[k];
        const DecodedPointId decoded = DecodePointId(points.ids[k], reference);
        ASSERT_EQ(decoded.region, layout.RegionOf(p.x, p.y)) << "point " << p.x << "," << p.y;
        RegionHandle& region = regions[decoded.region];
        if (!region) {
          StatusOr<RegionHandle> fetched = engine.Region(world, decoded.region);
          ASSERT_TRUE(fetched.ok()) << fetched.status().message();
          region = *fetched;
        }
        ASSERT_LT(decoded.index, region->points.size());
        EXPECT_EQ(region->points[decoded.index], p);
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(PlaneAlgorithms, PlaneDeterminismTest,
                         ::testing::ValuesIn(kPlaneAlgorithms),
                         [](const ::testing::TestParamInfo<WorldAlgorithm>& info) {
                           return std::string(WorldAlgorithmName(info.param));
                         });

// The comparison the tests above rely on, shown to catch planted faults in
// real output: one coordinate one ulp off, -0.0 for 0.0, a point missing,
// a point repeated, two ids swapped.
TEST(PlaneDeterminismCheckTest, SameBitsCatchesPlantedDifferences) {
  const World world = ValidWorld({.seed = 11});
  PlaneEngine engine(EngineOptions(1, int64_t{64} << 20));
  const PlanePoints real = MustPoints(engine, world, {-20, -20, 20, 20});
  ASSERT_GT(real.positions.size(), 100u);
  const std::vector<BitPoint> expected = SortedById(real);
  EXPECT_TRUE(SameBits(expected, SortedById(real)));

  PlanePoints nudged = real;
  nudged.positions[7].x = std::nextafter(nudged.positions[7].x, INFINITY);
  EXPECT_FALSE(SameBits(expected, SortedById(nudged)));

  PlanePoints signed_zero = real;
  signed_zero.positions[3] = {0.0, 0.0};
  std::vector<BitPoint> positive = SortedById(signed_zero);
  signed_zero.positions[3] = {-0.0, 0.0};
  EXPECT_FALSE(SameBits(positive, SortedById(signed_zero)));

  PlanePoints missing = real;
  missing.positions.pop_back();
  missing.ids.pop_back();
  EXPECT_FALSE(SameBits(expected, SortedById(missing)));

  PlanePoints repeated = real;
  repeated.positions.push_back(real.positions[0]);
  repeated.ids.push_back(real.ids[0]);
  EXPECT_FALSE(SameBits(expected, SortedById(repeated)));

  PlanePoints swapped = real;
  std::swap(swapped.ids[0], swapped.ids[1]);
  EXPECT_FALSE(SameBits(expected, SortedById(swapped)));
}

// The layout, field by field, as point_id.h documents it: i in bits 63..37,
// j in bits 36..10, k in bits 9..0, each region index taken mod 2^27.
TEST(PointIdTest, BitLayoutIsAsDocumented) {
  EXPECT_EQ(EncodePointId({0, 0}, 0), 0u);
  EXPECT_EQ(EncodePointId({1, 2}, 3), (uint64_t{1} << 37) | (uint64_t{2} << 10) | 3u);
  EXPECT_EQ(EncodePointId({0, 0}, 1023), 1023u);
  constexpr uint64_t kField = (uint64_t{1} << 27) - 1;
  EXPECT_EQ(EncodePointId({-1, -1}, 0), (kField << 37) | (kField << 10));
  EXPECT_EQ(EncodePointId({-1, -1}, 1023), ~uint64_t{0});
  // Regions 2^27 apart (2^31 d) share ids, the documented wrap.
  EXPECT_EQ(EncodePointId({5 + (int64_t{1} << 27), -7}, 9), EncodePointId({5, -7}, 9));
  EXPECT_EQ(EncodePointId({5, -7 - (int64_t{1} << 27)}, 9), EncodePointId({5, -7}, 9));
}

// Encode then decode gives the key back whenever the reference lies within
// 2^26 - 1 regions on each axis; at any distance the decoded key is congruent
// to the key mod 2^27. Keys span the whole precision range (|i|, |j| up to
// 2^28 regions = 2^32 d) and beyond, negative ones included.
TEST(PointIdTest, EncodeDecodeRoundTrip) {
  constexpr uint64_t kSeed = 0x1d0;
  SCOPED_TRACE(::testing::Message() << "seed " << kSeed);
  Rng rng(kSeed);
  constexpr int64_t kHalf = int64_t{1} << 26, kModulus = int64_t{1} << 27;
  const int64_t special[] = {0,
                             -1,
                             1,
                             kHalf - 1,
                             kHalf,
                             -kHalf,
                             kModulus - 1,
                             kModulus,
                             -kModulus,
                             (int64_t{1} << 28) - 1,
                             -(int64_t{1} << 28),
                             int64_t{1} << 40,
                             -(int64_t{1} << 40) - 3};
  auto random_index = [&] {
    switch (rng.Below(4)) {
      case 0:
        return static_cast<int64_t>(rng.Below(2 * (int64_t{1} << 28) + 1)) - (int64_t{1} << 28);
      case 1:
        return special[rng.Below(std::size(special))];
      case 2:
        return special[rng.Below(std::size(special))] + static_cast<int64_t>(rng.Below(5)) - 2;
      default:
        return static_cast<int64_t>(rng.Below(2001)) - 1000;
    }
  };
  auto random_offset = [&] {
    switch (rng.Below(3)) {
      case 0:
        return static_cast<int64_t>(rng.Below(2 * kHalf - 1)) - (kHalf - 1);
      case 1:
        return rng.Below(2) == 0 ? kHalf - 1 : -(kHalf - 1);
      default:
        return static_cast<int64_t>(rng.Below(7)) - 3;
    }
  };
  for (int n = 0; n < 200000; ++n) {
    const RegionKey key{random_index(), random_index()};
    const uint32_t index = static_cast<uint32_t>(n < 4 ? (n % 2) * 1023 : rng.Below(1024));
    const uint64_t id = EncodePointId(key, index);
    const RegionKey near{key.i + random_offset(), key.j + random_offset()};
    const DecodedPointId decoded = DecodePointId(id, near);
    ASSERT_EQ(decoded.region, key) << "key " << key.i << "," << key.j << " near " << near.i << ","
                                   << near.j << " index " << index;
    ASSERT_EQ(decoded.index, index);
    // Any reference at all: the right residue, and within 2^26 of the reference.
    const RegionKey anywhere{random_index(), random_index()};
    const DecodedPointId wrapped = DecodePointId(id, anywhere);
    ASSERT_EQ((wrapped.region.i - key.i) % kModulus, 0);
    ASSERT_EQ((wrapped.region.j - key.j) % kModulus, 0);
    ASSERT_LE(std::abs(wrapped.region.i - anywhere.i), kHalf);
    ASSERT_LE(std::abs(wrapped.region.j - anywhere.j), kHalf);
    ASSERT_EQ(wrapped.index, index);
  }
}

}  // namespace
}  // namespace scallop
