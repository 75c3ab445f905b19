// Every sampler, on rectangles and tori of random sizes and many seeds: every
// point inside the domain and every pair at least d apart, checked by brute
// force over all pairs (with wrap-around on a torus).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "scallop/random/rng.h"
#include "scallop/sampling/sampler.h"

namespace scallop {
namespace {

// Smallest pair distance squared over all pairs; O(N^2) on purpose.
double BruteForceClosestSquared(const std::vector<Vec2>& points, const Domain& domain) {
  const double w = domain.rect.Width(), h = domain.rect.Height();
  double best = INFINITY;
  for (size_t i = 0; i < points.size(); ++i) {
    for (size_t j = i + 1; j < points.size(); ++j) {
      double dx = std::abs(points[i].x - points[j].x), dy = std::abs(points[i].y - points[j].y);
      if (domain.torus) {
        dx = std::min(dx, w - dx);
        dy = std::min(dy, h - dy);
      }
      best = std::min(best, dx * dx + dy * dy);
    }
  }
  return best;
}

class SamplerSpacingTest : public ::testing::TestWithParam<Algorithm> {};

TEST_P(SamplerSpacingTest, NoPairCloserThanMinDistanceAndAllInside) {
  Rng dice(HashWords({2, static_cast<uint64_t>(GetParam())}));
  for (int trial = 0; trial < 12; ++trial) {
    SamplerOptions options;
    options.algorithm = GetParam();
    options.seed = dice.NextBits();
    options.min_distance = dice.Uniform(0.5, 2.0);
    options.domain.torus = trial % 2 == 1;
    const double x0 = dice.Uniform(-100, 100), y0 = dice.Uniform(-100, 100);
    const double side = options.min_distance * dice.Uniform(8.0, 20.0);
    options.domain.rect = {x0, y0, x0 + side * dice.Uniform(1.0, 2.0), y0 + side};
    options.density = dice.Uniform(1.05, 2.0);
    options.dart_failure_limit = 2000;
    options.best_candidate_factor = 2;
    SCOPED_TRACE(::testing::Message() << "seed " << options.seed << " torus "
                                      << options.domain.torus);
    auto points = Sample(options);
    ASSERT_TRUE(points.ok()) << points.status().message();
    ASSERT_GT(points->size(), 10u);
    for (const Vec2& p : *points) ASSERT_TRUE(options.domain.rect.Contains(p)) << p.x << "," << p.y;
    const double d2 = options.min_distance * options.min_distance;
    EXPECT_GE(BruteForceClosestSquared(*points, options.domain), d2);
  }
}

TEST_P(SamplerSpacingTest, SameSeedSameBits) {
  SamplerOptions options;
  options.algorithm = GetParam();
  options.domain.rect = {0, 0, 30, 30};
  options.seed = 77;
  options.dart_failure_limit = 2000;
  auto a = Sample(options);
  auto b = Sample(options);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(*a, *b);
  options.seed = 78;
  auto c = Sample(options);
  EXPECT_NE(*a, *c);
}

INSTANTIATE_TEST_SUITE_P(AllAlgorithms, SamplerSpacingTest,
                         ::testing::Values(Algorithm::kA1, Algorithm::kA2, Algorithm::kA3,
                                           Algorithm::kDartThrowing, Algorithm::kBestCandidate,
                                           Algorithm::kBridson),
                         [](const auto& info) {
                           std::string name(AlgorithmName(info.param));
                           for (char& c : name) c = c == '-' ? '_' : c;
                           return name;
                         });

// The brute-force check above must fail on a planted fault.
TEST(SamplerSpacingCheck, CatchesAPlantedClosePair) {
  std::vector<Vec2> points{{0, 0}, {3, 0}, {3, 0.999}};
  EXPECT_LT(BruteForceClosestSquared(points, {{-10, -10, 10, 10}, false}), 1.0);
  // On a torus, points near opposite edges are neighbours.
  std::vector<Vec2> wrapped{{0.2, 5}, {19.5, 5}};
  EXPECT_LT(BruteForceClosestSquared(wrapped, {{0, 0, 20, 20}, true}), 1.0);
}

TEST(SamplerOptionsValidation, NamesTheBadField) {
  SamplerOptions good;
  good.domain.rect = {0, 0, 10, 10};
  EXPECT_TRUE(ValidateSamplerOptions(good).ok());
  struct Case {
    SamplerOptions options;
    StatusCode code;
    std::string field;
  };
  auto with = [&](auto change) {
    SamplerOptions o = good;
    change(o);
    return o;
  };
  const Case cases[] = {
      {with([](auto& o) { o.min_distance = 0; }), StatusCode::kInvalidArgument, "min_distance"},
      {with([](auto& o) { o.min_distance = NAN; }), StatusCode::kInvalidArgument, "min_distance"},
      {with([](auto& o) { o.domain.rect.x1 = INFINITY; }), StatusCode::kInvalidArgument, "domain.x1"},
      {with([](auto& o) { o.domain.rect.y0 = NAN; }), StatusCode::kInvalidArgument, "domain.y0"},
      {with([](auto& o) { o.domain.rect.x1 = -1; }), StatusCode::kInvalidArgument, "x0 must be less"},
      {with([](auto& o) { o.domain.rect.y1 = 0; }), StatusCode::kInvalidArgument, "y0 must be less"},
      {with([](auto& o) { o.domain.rect.x0 = -1e12; }), StatusCode::kOutOfRange, "domain.x0"},
      {with([](auto& o) { o.domain.rect = {0, 0, 1e5, 1e5}; }), StatusCode::kInvalidArgument, "domain"},
      // Small in area, but too long and thin for its grids to fit in memory.
      {with([](auto& o) { o.domain.rect = {0, 0, 4e9, 1e-5}; }), StatusCode::kInvalidArgument,
       "domain: too large for min_distance once grown"},
      {with([](auto& o) { o.domain.torus = true; o.domain.rect = {0, 0, 7, 100}; }),
       StatusCode::kInvalidArgument, "torus"},
      {with([](auto& o) { o.algorithm = Algorithm::kA1; o.density = 1.0; }),
       StatusCode::kInvalidArgument, "density"},
      {with([](auto& o) { o.algorithm = Algorithm::kA2; o.density = 2.5; }),
       StatusCode::kInvalidArgument, "density"},
  };
  for (const Case& c : cases) {
    const Status status = ValidateSamplerOptions(c.options);
    EXPECT_EQ(status.code(), c.code) << status.message();
    EXPECT_NE(status.message().find(c.field), std::string::npos) << status.message();
    EXPECT_FALSE(Sample(c.options).ok());
  }
  EXPECT_TRUE(ParseAlgorithm("bridson").ok());
  EXPECT_FALSE(ParseAlgorithm("poisson").ok());
}

}  // namespace
}  // namespace scallop
