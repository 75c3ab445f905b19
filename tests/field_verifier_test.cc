// VerifyFieldDomain against brute force (every pair; dense probes with R at the probe) on
// sampler outputs with planted faults: a point moved into conflict, a point removed, a point
// put into a mask, a point moved outside. Each fault must be caught by both, and the verifier's
// certified gap bound must never be below a gap the probes find.
#include "scallop/verify/field_verifier.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "scallop/sampling/field_sampler.h"
#include "tests/field_test_fields.h"

namespace scallop {
namespace {

using field_test::FieldCase;

struct Case {
  Rect domain;
  RadiusField field;
  std::vector<Vec2> points;
};

Case MakeCase(FieldCase c, uint64_t seed, double ratio) {
  Rng rng(HashWords({seed, 5}));
  const double r_min = rng.Uniform(0.5, 2.0);
  const double side = std::max(3.0 * ratio, 24.0) * r_min;
  const double x0 = rng.Uniform(-100.0, 100.0);
  const double y0 = rng.Uniform(-100.0, 100.0);
  const Rect domain{x0, y0, x0 + side * rng.Uniform(1.0, 1.6), y0 + side * rng.Uniform(1.0, 1.6)};
  RadiusField field = field_test::MakeField(c, seed, r_min, ratio, domain);
  FieldSamplerOptions options;
  options.domain = domain;
  options.seed = seed;
  std::vector<Vec2> points = *SampleField(options, field);
  return {domain, field, std::move(points)};
}

// G at one spot against every point, by brute force.
double BruteGapAt(const std::vector<Vec2>& points, const RadiusField& field, Vec2 x) {
  double g = 1e300;
  const double rx = field.Evaluate(x);
  for (const Vec2& q : points) {
    g = std::min(g, std::hypot(x.x - q.x, x.y - q.y) - std::max(rx, field.Evaluate(q)));
  }
  return g;
}

const FieldCase kCases[] = {FieldCase::kConstant, FieldCase::kNoise, FieldCase::kRaster,
                            FieldCase::kMaskedRaster};

// The verifier's gap bound is an upper bound of every probed G, and its verdicts agree with
// brute force on clean outputs and on every removal fault.
TEST(FieldVerifierTest, AgreesWithBruteForceOnCleanAndHoledSets) {
  int caught = 0;
  int faults = 0;
  for (FieldCase c : kCases) {
    for (uint64_t seed = 1; seed <= 4; ++seed) {
      Case k = MakeCase(c, seed, c == FieldCase::kConstant ? 1.0 : 8.0);
      const FieldVerifyReport clean = *VerifyFieldDomain(k.points, k.domain, k.field);
      EXPECT_TRUE(clean.passed()) << field_test::CaseName(c) << " seed " << seed;
      EXPECT_EQ(clean.conflicts, field_test::BruteForceConflicts(k.points, k.field));
      // Planted: remove a point. Its own spot is then free (it kept the spacing from every
      // other point), by G(spot) = min_q |spot - q| - max(R(spot), R(q)) >= 0; a point whose
      // neighbours sit at exactly the spacing leaves a gap within the tolerance only, so the
      // victim is the one of 10 random points whose removal leaves the largest G.
      Rng rng(seed);
      size_t victim = 0;
      double victim_gap = -1e300;
      for (int t = 0; t < 10; ++t) {
        const size_t v = rng.Below(k.points.size());
        std::vector<Vec2> rest = k.points;
        rest.erase(rest.begin() + static_cast<std::ptrdiff_t>(v));
        const double g = BruteGapAt(rest, k.field, k.points[v]);
        if (g > victim_gap) {
          victim_gap = g;
          victim = v;
        }
      }
      std::vector<Vec2> holed = k.points;
      holed.erase(holed.begin() + static_cast<std::ptrdiff_t>(victim));
      const FieldVerifyReport report = *VerifyFieldDomain(holed, k.domain, k.field);
      const field_test::ProbeResult probe =
          field_test::BruteForceProbe(holed, k.field, k.domain, k.field.r_min() * 0.25, seed);
      EXPECT_GE(victim_gap, 0.0);
      EXPECT_GE(report.gap_bound, probe.worst_gap) << field_test::CaseName(c) << " seed " << seed;
      EXPECT_GE(report.gap_bound, victim_gap) << field_test::CaseName(c) << " seed " << seed;
      if (victim_gap > 1e-8 * k.field.r_max()) {
        ++faults;
        if (!report.maximal_ok) ++caught;
        EXPECT_FALSE(report.maximal_ok) << field_test::CaseName(c) << " seed " << seed;
      }
    }
  }
  EXPECT_GE(faults, 8);  // 9 of the 16 sets, as generated; every one must be caught
  std::printf("removal faults caught: %d of %d\n", caught, faults);
}

TEST(FieldVerifierTest, CatchesAPointMovedIntoConflict) {
  for (FieldCase c : kCases) {
    for (uint64_t seed = 1; seed <= 4; ++seed) {
      Case k = MakeCase(c, seed, c == FieldCase::kConstant ? 1.0 : 4.0);
      ASSERT_GE(k.points.size(), 2u);
      // Move point 1 to 90% of the way to point 0's spacing: conflict under the max rule.
      std::vector<Vec2> moved = k.points;
      const Vec2 p = moved[0];
      const double m = std::max(k.field.Evaluate(p), k.field.r_min());
      Vec2 target{p.x + 0.5 * m, p.y};
      if (!k.domain.Contains(target)) target = {p.x - 0.5 * m, p.y};
      moved[1] = target;
      const int64_t brute = field_test::BruteForceConflicts(moved, k.field);
      const FieldVerifyReport report = *VerifyFieldDomain(moved, k.domain, k.field);
      EXPECT_GT(brute, 0);
      EXPECT_EQ(report.conflicts, brute) << field_test::CaseName(c) << " seed " << seed;
      EXPECT_FALSE(report.passed());
      EXPECT_LT(report.min_spacing_ratio, 1.0);
    }
  }
}

TEST(FieldVerifierTest, CatchesAPointInAMaskOrOutside) {
  for (uint64_t seed = 1; seed <= 4; ++seed) {
    Case k = MakeCase(FieldCase::kMaskedRaster, seed, 4.0);
    // A masked spot: scan the domain for one.
    Vec2 masked_spot;
    bool found = false;
    for (double y = k.domain.y0; y < k.domain.y1 && !found; y += 0.1) {
      for (double x = k.domain.x0; x < k.domain.x1 && !found; x += 0.1) {
        if (k.field.IsMasked({x, y})) {
          masked_spot = {x, y};
          found = true;
        }
      }
    }
    ASSERT_TRUE(found) << "seed " << seed;
    std::vector<Vec2> bad = k.points;
    bad.push_back(masked_spot);
    FieldVerifyReport report = *VerifyFieldDomain(bad, k.domain, k.field);
    EXPECT_EQ(report.points_masked, 1);
    EXPECT_FALSE(report.passed());
    bad = k.points;
    bad.push_back({k.domain.x1, k.domain.y0});  // the half-open domain's right edge
    report = *VerifyFieldDomain(bad, k.domain, k.field);
    EXPECT_EQ(report.points_outside, 1);
    EXPECT_FALSE(report.passed());
  }
}

TEST(FieldVerifierTest, EmptySetIsNotMaximalAndBadInputIsRejected) {
  const RadiusField field = RadiusField::Constant(1.0);
  const std::vector<Vec2> none;
  const FieldVerifyReport report = *VerifyFieldDomain(none, {0, 0, 10, 10}, field);
  EXPECT_FALSE(report.maximal_ok);
  EXPECT_FALSE(VerifyFieldDomain(none, {0, 0, -1, 10}, field).ok());
  const std::vector<Vec2> nan_point = {{NAN, 0.0}};
  EXPECT_FALSE(VerifyFieldDomain(nan_point, {0, 0, 10, 10}, field).ok());
  FieldVerifyOptions options;
  options.max_tolerance = -1.0;
  EXPECT_FALSE(VerifyFieldDomain(none, {0, 0, 10, 10}, field, options).ok());
}

// options.stop (a Verify whose client has gone stops, as the Delaunay verifier does): a stop
// that never fires is polled once per 16,384 steps and changes nothing; one that fires at the
// k-th poll ends the run there with CANCELLED, in the pair scan and in the gap search.
TEST(FieldVerifierTest, StopIsPolledAndEndsTheRunWithCancelled) {
  const Rect domain{-150.0, -150.0, 150.0, 150.0};
  const RadiusField field = field_test::NoiseField(24, 1.0, 4.0);
  FieldSamplerOptions sampling;
  sampling.domain = domain;
  sampling.seed = 24;
  const std::vector<Vec2> points = *SampleField(sampling, field);
  const FieldVerifyReport plain = *VerifyFieldDomain(points, domain, field);
  ASSERT_TRUE(plain.passed());
  int polls = 0;
  FieldVerifyOptions never;
  never.stop = [&] { return ++polls < 0; };
  const FieldVerifyReport polled = *VerifyFieldDomain(points, domain, field, never);
  EXPECT_EQ(polled.gap_bound, plain.gap_bound);
  EXPECT_EQ(polled.pairs_checked, plain.pairs_checked);
  // The pair scan takes one step a point; the gap search one a cell judged, at least the
  // 150 x 150 tiles of r_max / 2.
  const auto steps_at_least = static_cast<int>(points.size()) + 150 * 150;
  EXPECT_GE(polls, steps_at_least / 16384) << points.size() << " points";
  ASSERT_GE(polls, 2);
  for (const int stop_at : {1, polls}) {
    int calls = 0;
    FieldVerifyOptions stopping;
    stopping.stop = [&] { return ++calls >= stop_at; };
    const StatusOr<FieldVerifyReport> stopped = VerifyFieldDomain(points, domain, field, stopping);
    ASSERT_FALSE(stopped.ok()) << stop_at;
    EXPECT_EQ(stopped.status().code(), StatusCode::kCancelled);
    EXPECT_EQ(calls, stop_at);
    // The window entry point (what Verify on a field world runs) polls the same way.
    calls = 0;
    EXPECT_EQ(VerifyFieldWindow(points, domain, field, stopping).status().code(),
              StatusCode::kCancelled);
  }
}

}  // namespace
}  // namespace scallop
