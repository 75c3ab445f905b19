// Pins the bits of SampleField and SampleFieldProblem on runs large enough to exercise every
// path of the growth and the sweep many thousand times (tens of thousands of points, ratios 8
// and 16, masks, a plane region's problem with exclusion disks): the goldens
// (FieldSamplerTest.GoldenOutputs, plane_golden_test) hold a few hundred points each, too few
// to catch a speed change that moves a point only rarely. Generator version 4: these hashes
// were taken before the speed work of issue 24 and must never change without a new version.
#include <gtest/gtest.h>

#include <bit>
#include <cstdio>
#include <vector>

#include "scallop/random/rng.h"
#include "scallop/sampling/field_sampler.h"
#include "tests/field_test_fields.h"

namespace scallop {
namespace {

uint64_t HashOf(const std::vector<Vec2>& points) {
  uint64_t h = points.size();
  for (const Vec2& p : points) {
    h = Mix64(h + std::bit_cast<uint64_t>(p.x));
    h = Mix64(h + std::bit_cast<uint64_t>(p.y));
  }
  return h;
}

std::vector<Vec2> Bounded(const RadiusField& field, const Rect& domain, uint64_t seed) {
  FieldSamplerOptions options;
  options.domain = domain;
  options.seed = seed;
  return *SampleField(options, field);
}

void ExpectHash(const char* name, const std::vector<Vec2>& points, uint64_t pinned) {
  std::printf("%s: %zu points, hash 0x%016llxULL\n", name, points.size(),
              static_cast<unsigned long long>(HashOf(points)));
  EXPECT_EQ(HashOf(points), pinned) << name;
}

TEST(FieldSamplerPinnedTest, BoundedRunsKeepTheirBits) {
  // The benchmark's kind of field (ratio 8), about 20k points.
  ExpectHash("noise 8", Bounded(field_test::NoiseField(2026, 1.0, 8.0), {0, 0, 650, 650}, 1),
             0x483ee6106e3d729cULL);
  // Ratio 16 off the origin, about 12k points.
  ExpectHash("noise 16", Bounded(field_test::NoiseField(5, 0.5, 16.0), {-1200, 300, -700, 800}, 2),
             0x70e412ceb522805aULL);
  // A masked raster, ratio 8, about 8k points.
  const Rect raster_domain{100, -50, 500, 350};
  ExpectHash("masked raster",
             Bounded(field_test::MakeField(field_test::FieldCase::kMaskedRaster, 3, 0.75, 8.0,
                                           raster_domain),
                     raster_domain, 3),
             0x34eecb223c99e188ULL);
}

// A plane region's problem: fixed points from an earlier run along one side (their strip
// closed), a stop rectangle, and exclusion disks (a layered world's earlier layer).
TEST(FieldSamplerPinnedTest, ProblemRunKeepsItsBits) {
  const RadiusField field = field_test::NoiseField(11, 0.5, 8.0);
  const std::vector<Vec2> earlier = Bounded(field, {0, 0, 200, 300}, 4);
  std::vector<Vec2> fixed;
  for (const Vec2& p : earlier) {
    if (p.x >= 150) fixed.push_back(p);
  }
  const std::vector<Rect> closed = {{160, 0, 190, 300}};
  Rng rng(12);
  std::vector<ExclusionDisk> exclusions;
  for (int k = 0; k < 60; ++k) {
    exclusions.push_back({{rng.Uniform(190, 400), rng.Uniform(0, 300)}, rng.Uniform(0.5, 6.0)});
  }
  SamplingProblem problem;
  problem.domain = Domain{{160, 0, 420, 300}, false};
  problem.fixed_points = fixed;
  problem.covered_rects = closed;
  problem.stop_when_covered = Rect{190, 20, 390, 280};
  problem.exclusions = exclusions;
  Rng run_rng(HashWords({13, 14}));
  std::vector<bool> unprocessed;
  const std::vector<Vec2> placed = SampleFieldProblem(problem, field, run_rng, &unprocessed);
  ExpectHash("problem", placed, 0xbe15063c4d759447ULL);
  int64_t left = 0;
  for (const bool u : unprocessed) left += u ? 1 : 0;
  EXPECT_EQ(left, 234);
  // The stream goes on where the run left it: the next region draws from it.
  EXPECT_EQ(run_rng.NextBits(), 0x1e2fa15ae284c457ULL);
}

}  // namespace
}  // namespace scallop
