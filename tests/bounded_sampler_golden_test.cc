// Golden hashes pin every bounded sampler, A1-A3 and the baselines, on a
// rectangle and on a torus: Sample() is promised to give the same bits on
// every machine and build (docs/determinism.md), so a change here is a bug
// unless it was meant, and then the generator version is bumped.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "scallop/random/rng.h"
#include "scallop/sampling/sampler.h"

namespace scallop {
namespace {

// Small domains (about 150 points), so the -O0 and emulated aarch64 builds
// of scripts/test-portability.sh run this in seconds; big enough that every
// sampler draws thousands of random numbers and takes many accept/reject
// decisions, any of which a one-ulp difference would flip.
SamplerOptions GoldenOptions(Algorithm algorithm, bool torus, uint64_t seed) {
  SamplerOptions options;
  options.algorithm = algorithm;
  // Off-origin, fractional corners: coordinates with rounding in them.
  options.domain =
      torus ? Domain{{-3.25, 1.5, 12.75, 13.5}, true} : Domain{{-7.25, 3.5, 9.75, 16.125}, false};
  options.min_distance = 1.0;
  options.density = UsesDensity(algorithm) ? 1.8 : 2.0;
  options.seed = seed;
  options.dart_failure_limit = 3000;  // the default 100000 would take seconds at -O0
  options.bridson_attempts = 30;
  options.best_candidate_factor = 10;
  return options;
}

// HashWords (random/rng.h) chained over the count and each point's x and y bits.
uint64_t PointsHash(const std::vector<Vec2>& points) {
  uint64_t h = HashWords({points.size()});
  for (const Vec2& p : points) {
    h = HashWords({h, std::bit_cast<uint64_t>(p.x), std::bit_cast<uint64_t>(p.y)});
  }
  return h;
}

uint64_t SampleHash(const SamplerOptions& options) {
  StatusOr<std::vector<Vec2>> points = Sample(options);
  EXPECT_TRUE(points.ok()) << points.status().message();
  if (!points.ok()) return 0;
  // A pinned empty or one-point set would pin next to nothing.
  EXPECT_GT(points->size(), 50u);
  return PointsHash(*points);
}

struct Golden {
  Algorithm algorithm;
  uint64_t rectangle;
  uint64_t torus;
};

// Computed with kGeneratorVersion 3 by the GCC 12 -O3 x86-64 build; the
// Clang, -O0 and aarch64 builds must agree (scripts/test-portability.sh).
// If one changes: unintended, it is a bug; intended, bump kGeneratorVersion
// (plane/world.h), say why in the commit, and paste the printed values.
constexpr Golden kGolden[] = {
    {Algorithm::kA1, 0x2336daed5e6b5694ULL, 0xa9e139fa876bbd1fULL},
    {Algorithm::kA2, 0x36de6ec3407fed13ULL, 0x59a94c40270bbd43ULL},
    {Algorithm::kA3, 0xa2b9b57f2687e1e6ULL, 0x819a5b3800ee9cedULL},
    {Algorithm::kDartThrowing, 0x8575ddb88a6ea7c9ULL, 0x065d57dab38346c7ULL},
    {Algorithm::kBestCandidate, 0x3aae657368f0fef7ULL, 0x206b6107081e5f26ULL},
    {Algorithm::kBridson, 0x0272735650094a8bULL, 0x0a52b22b3f33216fULL},
};
constexpr uint64_t kGoldenSeed = 2026;

TEST(BoundedSamplerGoldenTest, EverySamplerOnRectangleAndTorusHasItsPinnedHash) {
  for (const Golden& golden : kGolden) {
    const std::string name(AlgorithmName(golden.algorithm));
    const uint64_t rectangle = SampleHash(GoldenOptions(golden.algorithm, false, kGoldenSeed));
    const uint64_t torus = SampleHash(GoldenOptions(golden.algorithm, true, kGoldenSeed));
    EXPECT_EQ(rectangle, golden.rectangle)
        << name << " on the rectangle: got 0x" << std::hex << rectangle;
    EXPECT_EQ(torus, golden.torus) << name << " on the torus: got 0x" << std::hex << torus;
    std::printf("%s: rectangle 0x%016llxULL, torus 0x%016llxULL\n", name.c_str(),
                static_cast<unsigned long long>(rectangle), static_cast<unsigned long long>(torus));
  }
}

// Exhaustive dart throwing draws darts from a quadtree of uncovered cells, a
// path of its own: pinned apart.
TEST(BoundedSamplerGoldenTest, ExhaustiveDartThrowingHasItsPinnedHash) {
  SamplerOptions options = GoldenOptions(Algorithm::kDartThrowing, false, kGoldenSeed);
  options.dart_exhaustive = true;
  const uint64_t hash = SampleHash(options);
  EXPECT_EQ(hash, 0xadbc01d94db31b7dULL) << "got 0x" << std::hex << hash;
}

// A1 at density 2 is exact dart throwing, by cells with every cell open (on the torus with
// images across the edges): a path of its own, pinned apart. Until 2026-11-25 it was the paper's
// A1, restricted to spots within r' (docs/quality.md); world regions still use that one.
TEST(BoundedSamplerGoldenTest, ExactA1HasItsPinnedHash) {
  for (const bool torus : {false, true}) {
    SamplerOptions options = GoldenOptions(Algorithm::kA1, torus, kGoldenSeed);
    options.density = 2.0;
    const uint64_t hash = SampleHash(options);
    std::printf("exact a1: %s 0x%016llxULL\n", torus ? "torus" : "rectangle",
                static_cast<unsigned long long>(hash));
    EXPECT_EQ(hash, torus ? 0xef7de23d041a6f97ULL : 0x20b1d66f04e7a74fULL)
        << "got 0x" << std::hex << hash;
  }
}

// The pins can fail: another seed gives another hash for every sampler and
// domain, so a hash that ignored the points would be caught here.
TEST(BoundedSamplerGoldenTest, AnotherSeedGivesAnotherHash) {
  for (const Golden& golden : kGolden) {
    for (bool torus : {false, true}) {
      EXPECT_NE(SampleHash(GoldenOptions(golden.algorithm, torus, kGoldenSeed + 1)),
                SampleHash(GoldenOptions(golden.algorithm, torus, kGoldenSeed)))
          << AlgorithmName(golden.algorithm) << (torus ? " torus" : " rectangle");
    }
  }
}

}  // namespace
}  // namespace scallop
