// NearestLookup against its brute-force twin (nearest_oracle.h) on random
// positions of many worlds: in the open, exactly on seams and corners, on
// points, far from the origin and on the precision limit; plus its errors,
// its determinism and the maximality bounds docs/noise.md relies on.
#include "scallop/noise/nearest_lookup.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "scallop/plane/point_id.h"
#include "scallop/random/rng.h"
#include "tests/nearest_oracle.h"
#include "tests/test_worlds.h"

namespace scallop::testing {
namespace {

World WorldFor(WorldAlgorithm algorithm, uint64_t seed, double d = 1.0) {
  return ValidWorld({.seed = seed,
                     .min_distance = d,
                     .algorithm = algorithm,
                     .density = algorithm == WorldAlgorithm::kA2 ? 1.5 : 2.0});
}

// Compares every position's answer with the oracle; returns the mismatches
// (and reports the first few).
int CountMismatches(PlaneEngine& engine, NearestLookup& lookup, const World& world,
                    const std::vector<Vec2>& positions) {
  std::vector<NearestPoint> results(positions.size());
  const Status status = lookup.Nearest(world, positions, results);
  EXPECT_TRUE(status.ok()) << status.message();
  if (!status.ok()) return static_cast<int>(positions.size());
  int mismatches = 0;
  for (size_t k = 0; k < positions.size(); ++k) {
    const ::testing::AssertionResult same =
        SameNearest(OracleNearest(engine, world, positions[k]), results[k]);
    if (!same && ++mismatches <= 3) {
      ADD_FAILURE() << std::hexfloat << "at (" << positions[k].x << ", " << positions[k].y
                    << ") of " << world.Describe() << ": " << same.message();
    }
  }
  return mismatches;
}

std::vector<Vec2> RandomPositions(Rng& rng, Vec2 centre, double half, int count) {
  std::vector<Vec2> positions;
  for (int k = 0; k < count; ++k) {
    positions.push_back({centre.x + rng.Uniform(-half, half), centre.y + rng.Uniform(-half, half)});
  }
  return positions;
}

TEST(NearestLookupTest, RandomPositionsMatchBruteForceInEveryAlgorithm) {
  PlaneEngine engine({.threads = 1});
  NearestLookup lookup(engine);
  for (WorldAlgorithm algorithm : {WorldAlgorithm::kA1, WorldAlgorithm::kA2, WorldAlgorithm::kA3}) {
    for (uint64_t seed = 1; seed <= 3; ++seed) {
      SCOPED_TRACE(::testing::Message()
                   << "algorithm " << WorldAlgorithmName(algorithm) << " seed " << seed);
      Rng rng(HashWords({seed, 17}));
      const Vec2 centre{rng.Uniform(-1e4, 1e4), rng.Uniform(-1e4, 1e4)};
      const World world = WorldFor(algorithm, seed);
      EXPECT_EQ(CountMismatches(engine, lookup, world, RandomPositions(rng, centre, 40, 400)), 0);
    }
  }
  EXPECT_EQ(lookup.Stats().fallbacks, 0) << "a maximal world never needs the fallback";
}

TEST(NearestLookupTest, SeamsCornersAndPointsMatchBruteForce) {
  PlaneEngine engine({.threads = 1});
  NearestLookup lookup(engine);
  for (double d : {1.0, 0.37}) {
    const World world = WorldFor(WorldAlgorithm::kA3, 5, d);
    const RegionLayout layout(d);
    Rng rng(HashWords({5, 29}));
    std::vector<Vec2> positions;
    for (int k = 0; k < 300; ++k) {
      // A region edge, exactly and one ulp either side, against a random other coordinate.
      const Rect edges = layout.RegionRect(
          {static_cast<int64_t>(rng.Below(8)) - 4, static_cast<int64_t>(rng.Below(8)) - 4});
      const double along = rng.Uniform(edges.y0 - 2 * d, edges.y1 + 2 * d);
      double edge = edges.x0;
      if (k % 3 == 1) edge = std::nextafter(edge, -1e300);
      if (k % 3 == 2) edge = std::nextafter(edge, 1e300);
      positions.push_back(k % 2 ? Vec2{edge, along} : Vec2{along, edge});
      positions.push_back({edges.x0, edges.y0});  // a corner, where four regions meet
    }
    // The points themselves: F1 = 0 and the id is the point's own.
    StatusOr<PlanePoints> points = engine.Points(world, {-20 * d, -20 * d, 20 * d, 20 * d});
    ASSERT_TRUE(points.ok());
    for (size_t k = 0; k < points->positions.size(); k += 7)
      positions.push_back(points->positions[k]);
    SCOPED_TRACE(::testing::Message() << "d = " << d);
    EXPECT_EQ(CountMismatches(engine, lookup, world, positions), 0);

    std::vector<NearestPoint> results(1);
    ASSERT_TRUE(lookup.Nearest(world, {&points->positions[3], 1}, results).ok());
    EXPECT_EQ(results[0].f1, 0.0);
    EXPECT_EQ(results[0].id, points->ids[3]);
  }
}

// Batches of 1,024 positions or more find their grids through a dense
// window of regions about the first position (docs/noise.md, "Batches"):
// positions exactly on seams and an ulp either side, random ones, ones
// beyond the window, and a window about a corner of the precision range,
// part of it beyond the range. Grouped pairs of positions (AnswerEach) see
// every kind side by side.
TEST(NearestLookupTest, LargeBatchesThroughTheWindowMatchBruteForce) {
  PlaneEngine engine({.threads = 1});
  NearestLookup lookup(engine);
  const double d = 1.0;
  const World world = WorldFor(WorldAlgorithm::kA3, 13, d);
  const RegionLayout layout(d);
  const double limit = layout.precision_limit();
  for (const Vec2 centre : {Vec2{40, -30}, Vec2{limit - 5 * d, -limit + 5 * d}}) {
    SCOPED_TRACE(::testing::Message() << "window about " << centre.x << ", " << centre.y);
    Rng rng(HashWords({13, static_cast<uint64_t>(centre.x)}));
    std::vector<Vec2> positions = {centre};
    const RegionKey home = layout.RegionOf(centre.x, centre.y);
    while (positions.size() < 1400) {
      const Rect edges = layout.RegionRect({home.i + static_cast<int64_t>(rng.Below(5)) - 2,
                                            home.j + static_cast<int64_t>(rng.Below(5)) - 2});
      const double along = rng.Uniform(edges.y0, edges.y1);
      double edge = positions.size() % 2 ? edges.x0 : edges.x1;
      if (positions.size() % 3 == 1) edge = std::nextafter(edge, -1e300);
      if (positions.size() % 3 == 2) edge = std::nextafter(edge, 1e300);
      const Vec2 on_seam = positions.size() % 4 < 2 ? Vec2{edge, along} : Vec2{along, edge};
      positions.push_back(
          {std::clamp(on_seam.x, -limit, limit), std::clamp(on_seam.y, -limit, limit)});
      positions.push_back({std::clamp(centre.x + rng.Uniform(-60, 60), -limit, limit),
                           std::clamp(centre.y + rng.Uniform(-60, 60), -limit, limit)});
      if (rng.Below(8) == 0) {  // beyond the window's 64 x 64 regions, when that is in range
        const double far = centre.x > 0 ? -2000 : 2000;
        positions.push_back({centre.x + far + rng.Uniform(-40, 40),
                             std::clamp(centre.y + rng.Uniform(-40, 40), -limit, limit)});
      }
    }
    positions.push_back({limit, -limit});  // on the range's corner
    std::vector<NearestPoint> results(positions.size());
    const Status status = lookup.Nearest(world, positions, results);
    ASSERT_TRUE(status.ok()) << status.message();
    int mismatches = 0, rotated_mismatches = 0;
    for (size_t k = 0; k < positions.size(); ++k) {
      const NearestPoint truth = OracleNearest(engine, world, positions[k]);
      if (!SameNearest(truth, results[k]) && ++mismatches <= 3) {
        ADD_FAILURE() << std::hexfloat << "at (" << positions[k].x << ", " << positions[k].y << ")";
      }
      // Planted fault: each answer in its neighbour's slot must be seen.
      if (!SameNearest(truth, results[(k + 1) % results.size()])) ++rotated_mismatches;
    }
    EXPECT_EQ(mismatches, 0);
    EXPECT_GT(rotated_mismatches, static_cast<int>(positions.size()) * 9 / 10);
  }
  EXPECT_EQ(lookup.Stats().fallbacks, 0);
}

TEST(NearestLookupTest, FarFromTheOriginAndOnThePrecisionLimit) {
  PlaneEngine engine({.threads = 1});
  NearestLookup lookup(engine);
  for (double d : {1.0, 0.37}) {
    const World world = WorldFor(WorldAlgorithm::kA3, 9, d);
    const double limit = RegionLayout(d).precision_limit();
    Rng rng(HashWords({9, 31}));
    std::vector<Vec2> positions;
    for (double sx : {-1.0, 1.0}) {
      for (double sy : {-1.0, 1.0}) {
        positions.push_back({sx * limit, sy * limit});  // the corners of the range
        for (int k = 0; k < 40; ++k) {
          positions.push_back(
              {sx * (limit - rng.Uniform(0, 30 * d)), sy * (limit - rng.Uniform(0, 30 * d))});
          positions.push_back({sx * limit, sy * (limit - rng.Uniform(0, 30 * d))});
        }
      }
    }
    SCOPED_TRACE(::testing::Message() << "d = " << d);
    EXPECT_EQ(CountMismatches(engine, lookup, world, positions), 0);
  }
  EXPECT_EQ(lookup.Stats().fallbacks, 0);
}

TEST(NearestLookupTest, BruteForceMethodAgreesAndRunsOnlyTheFallback) {
  PlaneEngine engine({.threads = 1});
  NearestLookup grid(engine);
  NearestLookup brute(engine, {.method = NearestMethod::kBruteForce});
  const World world = WorldFor(WorldAlgorithm::kA1, 21);
  Rng rng(21);
  const std::vector<Vec2> positions = RandomPositions(rng, {-300, 700}, 30, 300);
  std::vector<NearestPoint> from_grid(positions.size()), from_brute(positions.size());
  ASSERT_TRUE(grid.Nearest(world, positions, from_grid).ok());
  ASSERT_TRUE(brute.Nearest(world, positions, from_brute).ok());
  for (size_t k = 0; k < positions.size(); ++k) {
    EXPECT_TRUE(SameNearest(from_brute[k], from_grid[k])) << k;
  }
  EXPECT_EQ(brute.Stats().grids_built, 0);
  EXPECT_GT(grid.Stats().grids_built, 0);
}

// The bounds docs/noise.md uses: F1 < d (1 + tol) and F1 + F2 < 2 d (1 + tol),
// with the verifier's tolerance; and F1 is 1-Lipschitz.
TEST(NearestLookupTest, MaximalityBoundsAndContinuityHold) {
  PlaneEngine engine({.threads = 1});
  NearestLookup lookup(engine);
  const double tolerance = 1e-6;  // above MaximalityTolerance near the origin
  for (WorldAlgorithm algorithm : {WorldAlgorithm::kA1, WorldAlgorithm::kA2, WorldAlgorithm::kA3}) {
    const World world = WorldFor(algorithm, 4);
    Rng rng(HashWords({4, static_cast<uint64_t>(algorithm)}));
    std::vector<Vec2> positions = RandomPositions(rng, {0, 0}, 60, 4000);
    std::vector<Vec2> nudged;
    for (const Vec2& p : positions) nudged.push_back({p.x + 1e-3, p.y - 2e-3});
    std::vector<NearestPoint> results(positions.size()), nudged_results(positions.size());
    ASSERT_TRUE(lookup.Nearest(world, positions, results).ok());
    ASSERT_TRUE(lookup.Nearest(world, nudged, nudged_results).ok());
    double worst_f1 = 0, worst_sum = 0;
    for (size_t k = 0; k < positions.size(); ++k) {
      worst_f1 = std::max(worst_f1, results[k].f1);
      worst_sum = std::max(worst_sum, results[k].f1 + results[k].f2);
      EXPECT_LE(results[k].f1, results[k].f2);
      EXPECT_LE(std::abs(results[k].f1 - nudged_results[k].f1), std::hypot(1e-3, 2e-3) * 1.000001);
      EXPECT_GE(results[k].cell_value, 0.0);
      EXPECT_LT(results[k].cell_value, 1.0);
    }
    EXPECT_LT(worst_f1, 1 + tolerance) << WorldAlgorithmName(algorithm);
    EXPECT_LT(worst_sum, 2 * (1 + tolerance)) << WorldAlgorithmName(algorithm);
    std::cout << WorldAlgorithmName(algorithm) << ": largest F1 " << worst_f1
              << " d, largest F1 + F2 " << worst_sum << " d\n";
  }
}

TEST(NearestLookupTest, SameBitsWhateverTheOrderBatchingCacheOrThread) {
  PlaneEngine engine({.threads = 2});
  const World world = WorldFor(WorldAlgorithm::kA3, 77);
  Rng rng(77);
  const std::vector<Vec2> positions = RandomPositions(rng, {100, -100}, 100, 2000);
  NearestLookup lookup(engine);
  std::vector<NearestPoint> reference(positions.size());
  ASSERT_TRUE(lookup.Nearest(world, positions, reference).ok());

  // Reversed, one at a time, through a cache too small to keep any grid.
  NearestLookup starved(engine, {.cache_bytes = 0});
  for (size_t n = positions.size(); n-- > 0;) {
    std::vector<NearestPoint> one(1);
    ASSERT_TRUE(starved.Nearest(world, {&positions[n], 1}, one).ok());
    EXPECT_TRUE(SameNearest(reference[n], one[0])) << n;
  }
  EXPECT_EQ(starved.Stats().grids_cached, 0);

  // Two threads sharing a fresh lookup, each half the batch.
  NearestLookup shared(engine);
  const std::vector<NearestPoint> halves = testing::NearestOnTwoThreads(shared, world, positions);
  for (size_t k = 0; k < positions.size(); ++k) EXPECT_TRUE(SameNearest(reference[k], halves[k]));
}

TEST(NearestLookupTest, RejectsBadPositionsNamingThem) {
  PlaneEngine engine({.threads = 1});
  NearestLookup lookup(engine);
  const World world = WorldFor(WorldAlgorithm::kA3, 1, 0.5);
  std::vector<NearestPoint> results(3);
  const std::vector<Vec2> not_finite{{0, 0}, {1, 1}, {2, std::nan("")}};
  Status status = lookup.Nearest(world, not_finite, results);
  EXPECT_EQ(status.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(status.message().find("positions[2].y"), std::string::npos) << status.message();

  const double limit = 0x1.0p32 * 0.5;
  const std::vector<Vec2> beyond{{0, 0}, {std::nextafter(-limit, -1e300), 0}, {0, 0}};
  status = lookup.Nearest(world, beyond, results);
  EXPECT_EQ(status.code(), StatusCode::kOutOfRange);
  EXPECT_NE(status.message().find("positions[1].x"), std::string::npos) << status.message();
  const std::vector<Vec2> on_limit{{-limit, limit}, {limit, -limit}, {0, 0}};
  EXPECT_TRUE(lookup.Nearest(world, on_limit, results).ok());

  std::vector<NearestPoint> too_few(2);
  EXPECT_EQ(lookup.Nearest(world, on_limit, too_few).code(), StatusCode::kInvalidArgument);
}

// Large batches find regions met before through the window without testing
// the range: only regions with a region of the range on every side enter it.
// So a bad position after many good ones about a corner of the range, in
// its edge regions and those next to them, must still be caught and named,
// with nothing written. At d = 0.73, -limit less an ulp rounds into the
// lowest region of the range ((p * (1/S)) is exactly -n): a window that
// admitted edge regions answered it (the planted fault this catches).
TEST(NearestLookupTest, LargeBatchesRejectBadPositionsNearTheLimit) {
  PlaneEngine engine({.threads = 1});
  NearestLookup lookup(engine);
  for (double d : {1.0, 0.73}) {
    SCOPED_TRACE(::testing::Message() << "d = " << d);
    const World world = WorldFor(WorldAlgorithm::kA3, 5, d);
    const double limit = RegionLayout(d).precision_limit();
    Rng rng(HashWords({5, 77}));
    std::vector<Vec2> positions;  // within 40 d of the corner (limit, -limit)
    for (int k = 0; k < 1500; ++k) {
      positions.push_back({limit - rng.Uniform(0, 40 * d), -limit + rng.Uniform(0, 40 * d)});
    }
    EXPECT_EQ(CountMismatches(engine, lookup, world, positions), 0);
    const size_t bad = 1200;  // after every region about the corner has been met
    const double beyond = std::nextafter(limit, 1e300);
    struct BadPosition {
      Vec2 position;
      StatusCode code;
      std::string field;
    };
    const BadPosition cases[] = {
        {{beyond, -limit + 20 * d}, StatusCode::kOutOfRange, ".x"},
        {{limit - 20 * d, -beyond}, StatusCode::kOutOfRange, ".y"},
        {{beyond, -beyond}, StatusCode::kOutOfRange, ".x"},
        {{std::nan(""), -limit + 20 * d}, StatusCode::kInvalidArgument, ".x"},
        {{limit - 20 * d, -std::numeric_limits<double>::infinity()},
         StatusCode::kInvalidArgument,
         ".y"}};
    for (const BadPosition& c : cases) {
      std::vector<Vec2> batch = positions;
      batch[bad] = c.position;
      NearestPoint untouched;
      untouched.id = 12345;
      std::vector<NearestPoint> results(batch.size(), untouched);
      const Status status = lookup.Nearest(world, batch, results);
      EXPECT_EQ(status.code(), c.code) << status.message();
      const std::string field = "positions[" + std::to_string(bad) + "]" + c.field;
      EXPECT_NE(status.message().find(field), std::string::npos) << status.message();
      EXPECT_TRUE(std::all_of(results.begin(), results.end(),
                              [](const NearestPoint& r) { return r.id == 12345; }));
    }
  }
}

// The comparison above must notice a wrong answer: planted faults in one
// field each, and a lookup that ignores the neighbouring regions.
TEST(NearestLookupTest, ComparisonCatchesPlantedFaults) {
  PlaneEngine engine({.threads = 1});
  const World world = WorldFor(WorldAlgorithm::kA3, 3);
  const Vec2 p{15.9, 8.0};  // 0.1 d from the seam at x = 16
  const NearestPoint truth = OracleNearest(engine, world, p);
  EXPECT_TRUE(SameNearest(truth, truth));
  NearestPoint fault = truth;
  fault.f2 = std::nextafter(fault.f2, 10.0);
  EXPECT_FALSE(SameNearest(truth, fault));
  fault = truth;
  std::swap(fault.id, fault.second_id);
  EXPECT_FALSE(SameNearest(truth, fault));
  fault = truth;
  fault.cell_value = CellValue(truth.id + 1);
  EXPECT_FALSE(SameNearest(truth, fault));

  // A grid of region (0, 0) built from its own points only misses the
  // neighbours across the seam: positions near it must come out wrong.
  StatusOr<RegionHandle> region = engine.Region(world, {0, 0});
  ASSERT_TRUE(region.ok());
  std::vector<uint64_t> ids;
  for (size_t k = 0; k < (*region)->points.size(); ++k) ids.push_back(EncodePointId({0, 0}, k));
  const NearestSearchGrid own_only(1.0, {0, 0}, (*region)->points, ids);
  Rng rng(3);
  int wrong = 0;
  for (int k = 0; k < 200; ++k) {
    const Vec2 q{rng.Uniform(14, 16), rng.Uniform(0, 16)};
    TwoNearest best;
    if (!own_only.FindTwoNearest(q, best)) continue;
    const NearestPoint truth_q = OracleNearest(engine, world, q);
    if (best.id1 != truth_q.id || best.id2 != truth_q.second_id) ++wrong;
  }
  EXPECT_GT(wrong, 10);
}

}  // namespace
}  // namespace scallop::testing
