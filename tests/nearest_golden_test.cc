// Golden hashes pin NearestLookup's answers (ids, F1, F2, nearest points,
// cell values) at fixed positions of a fixed world per algorithm. Answers are
// promised bit for bit on every machine (the x86 four-lane first pass and
// the two-lane one of other CPUs alike), so a change here is a bug unless
// the generator version was bumped on purpose.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "scallop/noise/nearest_lookup.h"
#include "scallop/random/rng.h"
#include "tests/test_worlds.h"

namespace scallop {
namespace {

World GoldenWorld(WorldAlgorithm algorithm, uint64_t seed) {
  return ValidWorld({.seed = seed,
                     .min_distance = 1.0,
                     .algorithm = algorithm,
                     .density = UsesDensity(algorithm) ? 1.8 : 2.0});
}

// 192 positions: 128 about the origin across four regions and their seams
// (both signs), 64 about (-1e5, 3e5), where coordinates carry rounding.
std::vector<Vec2> GoldenPositions() {
  Rng rng(0x5ca11095);
  std::vector<Vec2> positions;
  for (int k = 0; k < 128; ++k) positions.push_back({rng.Uniform(-16, 16), rng.Uniform(-16, 16)});
  for (int k = 0; k < 64; ++k) {
    positions.push_back({-1e5 + rng.Uniform(0, 20), 3e5 + rng.Uniform(0, 20)});
  }
  return positions;
}

// HashWords (random/rng.h) chained over every field of every answer.
uint64_t AnswersHash(WorldAlgorithm algorithm, uint64_t seed) {
  PlaneEngine engine(PlaneEngineOptions{});
  NearestLookup lookup(engine);
  const std::vector<Vec2> positions = GoldenPositions();
  std::vector<NearestPoint> results(positions.size());
  const Status status = lookup.Nearest(GoldenWorld(algorithm, seed), positions, results);
  EXPECT_TRUE(status.ok()) << status.message();
  uint64_t h = HashWords({results.size()});
  for (const NearestPoint& n : results) {
    h = HashWords({h, n.id, std::bit_cast<uint64_t>(n.position.x),
                   std::bit_cast<uint64_t>(n.position.y), std::bit_cast<uint64_t>(n.f1),
                   std::bit_cast<uint64_t>(n.f2), n.second_id,
                   std::bit_cast<uint64_t>(n.cell_value)});
  }
  return h;
}

struct Golden {
  WorldAlgorithm algorithm;
  uint64_t hash;
};

// Computed with kGeneratorVersion 4 by the GCC 12 -O3 x86-64 build (four
// lanes); the Clang, -O0 and aarch64 builds must agree. If one changes:
// unintended, it is a bug; intended, bump kGeneratorVersion (plane/world.h)
// and paste the printed values.
constexpr Golden kGolden[] = {
    {WorldAlgorithm::kA1, 0xc3ec7ef8803c1e6eULL},
    {WorldAlgorithm::kA2, 0xa2efd23ae4b9578fULL},
    {WorldAlgorithm::kA3, 0xc96f77bff0a37834ULL},
};
constexpr uint64_t kGoldenSeed = 7;

TEST(NearestGoldenTest, AnswersAtFixedPositionsHaveTheirPinnedHashes) {
  for (const Golden& golden : kGolden) {
    const std::string name(WorldAlgorithmName(golden.algorithm));
    const uint64_t hash = AnswersHash(golden.algorithm, kGoldenSeed);
    EXPECT_EQ(hash, golden.hash) << name << ": got 0x" << std::hex << hash;
    std::printf("%s: 0x%016llxULL\n", name.c_str(), static_cast<unsigned long long>(hash));
  }
}

// The pins can fail: another world seed moves the points, so the answers.
TEST(NearestGoldenTest, AnotherSeedGivesAnotherHash) {
  for (const Golden& golden : kGolden) {
    EXPECT_NE(AnswersHash(golden.algorithm, kGoldenSeed + 1),
              AnswersHash(golden.algorithm, kGoldenSeed))
        << WorldAlgorithmName(golden.algorithm);
  }
}

}  // namespace
}  // namespace scallop
