// The maximal samplers (A1, A2, A3, exhaustive dart throwing) judged by the
// Delaunay verifier on random rectangles and tori: spacing and maximality must
// both hold. Non-maximal baselines and planted faults show the checks can fail.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "scallop/geometry/scalloped_region.h"
#include "scallop/random/rng.h"
#include "scallop/sampling/sampler.h"
#include "scallop/sampling/spacing.h"
#include "scallop/verify/delaunay_verifier.h"

namespace scallop {
namespace {

// One sampler configuration under test.
struct Config {
  Algorithm algorithm;
  double density;   // A1, A2 only
  bool exhaustive;  // dart throwing only
};

std::string Describe(const Config& config) {
  // snprintf rather than string concatenation, which trips GCC 12's -Wrestrict
  // false positive at -O3 (and CI builds with -Werror).
  char name[64];
  const std::string algorithm(AlgorithmName(config.algorithm));
  if (UsesDensity(config.algorithm)) {
    std::snprintf(name, sizeof name, "%s@%.2f", algorithm.c_str(), config.density);
  } else {
    std::snprintf(name, sizeof name, "%s%s", algorithm.c_str(),
                  config.exhaustive ? "-exhaustive" : "");
  }
  return name;
}

// Every maximal configuration: A2 at several densities because r' changes
// which neighbourhoods exist, and hence where slivers and gaps can hide.
const Config kMaximalConfigs[] = {
    {Algorithm::kA1, 2.0, false},          {Algorithm::kA1, 1.3, false},
    {Algorithm::kA2, 2.0, false},          {Algorithm::kA2, 1.5, false},
    {Algorithm::kA2, 1.1, false},          {Algorithm::kA3, 2.0, false},
    {Algorithm::kDartThrowing, 2.0, true},
};

SamplerOptions OptionsFor(const Config& config, const Domain& domain, double d, uint64_t seed) {
  SamplerOptions options;
  options.algorithm = config.algorithm;
  options.density = config.density;
  options.dart_exhaustive = config.exhaustive;
  options.domain = domain;
  options.min_distance = d;
  options.seed = seed;
  return options;
}

std::vector<Vec2> MustSample(const SamplerOptions& options) {
  StatusOr<std::vector<Vec2>> points = Sample(options);
  EXPECT_TRUE(points.ok()) << points.status().message();
  return points.ok() ? std::move(*points) : std::vector<Vec2>{};
}

VerifyReport MustVerify(const std::vector<Vec2>& points, const Domain& domain, double d,
                        const VerifyOptions& verify_options = {}) {
  StatusOr<VerifyReport> report = VerifyDomain(points, domain, d, verify_options);
  EXPECT_TRUE(report.ok()) << report.status().message();
  return report.ok() ? *report : VerifyReport{};
}

// A random domain: d in [0.25, 4], corners offset by up to +-500 d (so many
// domains straddle or lie wholly at negative coordinates). Tori have sides
// 8 d..40 d (8 d is the validated minimum); rectangles 0.3 d..40 d, so thin
// strips narrower than d, where every point is squeezed by two edges, occur.
Domain RandomDomain(Rng& dice, bool torus, double d) {
  const double x0 = d * dice.Uniform(-500, 500), y0 = d * dice.Uniform(-500, 500);
  const double shortest = torus ? 8.0 : 0.3;
  const double width = d * dice.Uniform(shortest, 40.0), height = d * dice.Uniform(shortest, 40.0);
  return {{x0, y0, x0 + width, y0 + height}, torus};
}

// Squared distance under the domain's metric (minimum image on a torus).
double PairSquaredDistance(Vec2 p, Vec2 q, const Domain& domain) {
  double dx = std::abs(p.x - q.x), dy = std::abs(p.y - q.y);
  if (domain.torus) {
    dx = std::min(dx, domain.rect.Width() - dx);
    dy = std::min(dy, domain.rect.Height() - dy);
  }
  return dx * dx + dy * dy;
}

// Index of the point nearest `spot` other than `skip`; brute force on purpose.
size_t NearestPoint(const std::vector<Vec2>& points, Vec2 spot, const Domain& domain,
                    size_t skip = SIZE_MAX) {
  size_t best = SIZE_MAX;
  double best_squared = INFINITY;
  for (size_t i = 0; i < points.size(); ++i) {
    const double squared = PairSquaredDistance(points[i], spot, domain);
    if (i != skip && squared < best_squared) {
      best_squared = squared;
      best = i;
    }
  }
  return best;
}

Vec2 Centre(const Rect& rect) { return {0.5 * (rect.x0 + rect.x1), 0.5 * (rect.y0 + rect.y1)}; }

// Wraps p into the half-open torus rectangle.
Vec2 Wrap(Vec2 p, const Rect& rect) {
  const auto wrap = [](double v, double lo, double side) {
    const double w = lo + std::fmod(std::fmod(v - lo, side) + side, side);
    return w < lo + side ? w : lo;
  };
  return {wrap(p.x, rect.x0, rect.Width()), wrap(p.y, rect.y0, rect.Height())};
}

TEST(SamplerMaximalityTest, MaximalSamplersPassTheVerifier) {
  // The worst largest empty circle / d seen, per configuration and overall:
  // the samplers keep SpacingFor(d, M) = d (1 + 2^-32) here, so values up to
  // 1 + 2.3e-10 are expected; the verifier accepts up to 1 + 1e-9.
  double worst_ratio = 0.0;
  std::string worst_run;
  uint64_t worst_seed = 0;
  std::string per_config;
  int runs = 0;
  for (const Config& config : kMaximalConfigs) {
    Rng dice(HashWords({0x3a, static_cast<uint64_t>(config.algorithm),
                        static_cast<uint64_t>(config.density * 100)}));
    double config_worst = 0.0;
    for (int trial = 0; trial < 16; ++trial) {
      const double d = dice.Uniform(0.25, 4.0);
      const Domain domain = RandomDomain(dice, trial % 2 == 1, d);
      const uint64_t seed = dice.NextBits();
      SCOPED_TRACE(::testing::Message()
                   << Describe(config) << " seed " << seed << " d " << d << " torus "
                   << domain.torus << " rect [" << domain.rect.x0 << ", " << domain.rect.x1
                   << ") x [" << domain.rect.y0 << ", " << domain.rect.y1 << ")");
      const std::vector<Vec2> points = MustSample(OptionsFor(config, domain, d, seed));
      ASSERT_FALSE(points.empty());
      const VerifyReport report = MustVerify(points, domain, d);
      EXPECT_EQ(report.points_checked, static_cast<int64_t>(points.size()));
      EXPECT_EQ(report.points_outside, 0);
      EXPECT_TRUE(report.spacing_ok)
          << report.spacing_violations << " pairs closer than d, closest "
          << report.min_distance / d << " d";
      EXPECT_TRUE(report.maximal_ok)
          << "empty circle of radius " << report.largest_empty_circle / d << " d at ("
          << report.largest_empty_centre.x << ", " << report.largest_empty_centre.y << ")";
      const double ratio = report.largest_empty_circle / d;
      config_worst = std::max(config_worst, ratio);
      if (ratio > worst_ratio) {
        worst_ratio = ratio;
        worst_run = Describe(config);
        worst_seed = seed;
      }
      ++runs;
    }
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, " %s %.12f", Describe(config).c_str(), config_worst);
    per_config += buffer;
  }
  std::printf("worst largest empty circle / d over %d runs: %.12f (%s seed %llu); per config:%s\n",
              runs, worst_ratio, worst_run.c_str(), static_cast<unsigned long long>(worst_seed),
              per_config.c_str());
}

// The verifier can say "not maximal" on real sampler output: plain dart
// throwing that gives up after 20 misses in a row, and Bridson (30 tries per
// active point), both leave holes. Their spacing is still right.
TEST(SamplerMaximalityTest, NonMaximalBaselinesAreCaught) {
  const Config baselines[] = {{Algorithm::kDartThrowing, 2.0, false},
                              {Algorithm::kBridson, 2.0, false}};
  for (const Config& config : baselines) {
    Rng dice(HashWords({0x3b, static_cast<uint64_t>(config.algorithm)}));
    int holes = 0;
    for (int trial = 0; trial < 6; ++trial) {
      const double d = dice.Uniform(0.5, 2.0);
      const Domain domain = RandomDomain(dice, trial % 2 == 1, d);
      SamplerOptions options = OptionsFor(config, domain, d, dice.NextBits());
      options.dart_failure_limit = 20;
      SCOPED_TRACE(::testing::Message() << Describe(config) << " seed " << options.seed);
      const std::vector<Vec2> points = MustSample(options);
      const VerifyReport report = MustVerify(points, domain, d);
      EXPECT_TRUE(report.spacing_ok);
      if (!report.maximal_ok) {
        // A hole must be a genuine one, not a rounding-sized excess.
        EXPECT_GT(report.largest_empty_circle, 1.001 * d);
        ++holes;
      }
    }
    EXPECT_GE(holes, 1) << Describe(config) << " looked maximal in every run";
  }
}

// Planted faults on real output: the verifier must notice one missing point
// and one point pushed to 0.99 d of its neighbour, including across a torus seam.
TEST(SamplerMaximalityTest, PlantedFaultsOnSamplerOutputAreCaught) {
  Rng dice(0x3c);
  for (const Config& config : kMaximalConfigs) {
    for (const bool torus : {false, true}) {
      const double d = dice.Uniform(0.5, 2.0);
      const double x0 = d * dice.Uniform(-300, 300), y0 = d * dice.Uniform(-300, 300);
      // At least 12 d a side, so the centre point's neighbourhood is interior.
      const Domain domain{{x0, y0, x0 + 14 * d, y0 + 12 * d}, torus};
      const uint64_t seed = dice.NextBits();
      SCOPED_TRACE(::testing::Message()
                   << Describe(config) << " seed " << seed << " torus " << torus);
      const std::vector<Vec2> points = MustSample(OptionsFor(config, domain, d, seed));
      ASSERT_GT(points.size(), 20u);
      ASSERT_TRUE(MustVerify(points, domain, d).passed());
      const size_t centre = NearestPoint(points, Centre(domain.rect), domain);

      // Removing a point uncovers at least its own spot, which was d or more
      // from every other point; with its Voronoi cell merged into its
      // neighbours' the hole is larger than d.
      std::vector<Vec2> removed = points;
      removed.erase(removed.begin() + static_cast<std::ptrdiff_t>(centre));
      const VerifyReport hole = MustVerify(removed, domain, d);
      EXPECT_TRUE(hole.spacing_ok);
      EXPECT_FALSE(hole.maximal_ok) << "largest empty circle " << hole.largest_empty_circle / d;
      EXPECT_GE(hole.largest_empty_circle, d);

      // Moving the centre point to 0.99 d of its nearest neighbour (along the
      // line between them) makes a pair too close; only the moved point's
      // pairs changed, so the closest pair must involve it.
      const size_t neighbour = NearestPoint(points, points[centre], domain, centre);
      std::vector<Vec2> moved = points;
      const Vec2 offset = points[centre] - points[neighbour];
      moved[centre] = points[neighbour] + (0.99 * d / Length(offset)) * offset;
      const VerifyReport close = MustVerify(moved, domain, d);
      EXPECT_FALSE(close.spacing_ok);
      EXPECT_GE(close.spacing_violations, 1);
      EXPECT_LE(close.min_distance, 0.99 * d * (1 + 1e-12));
      EXPECT_TRUE(close.closest_index_a == static_cast<int64_t>(centre) ||
                  close.closest_index_b == static_cast<int64_t>(centre));

      if (torus) {
        // Across the seam: the centre point moves to 0.99 d left of the
        // leftmost point, which wraps it to the right edge; the pair is close
        // only under the torus metric.
        size_t leftmost = 0;
        for (size_t i = 0; i < points.size(); ++i) {
          if (points[i].x < points[leftmost].x) leftmost = i;
        }
        ASSERT_LT(points[leftmost].x, domain.rect.x0 + 0.99 * d);
        std::vector<Vec2> seam = points;
        seam[centre] = Wrap(points[leftmost] - Vec2{0.99 * d, 0.0}, domain.rect);
        ASSERT_GT(seam[centre].x, domain.rect.x1 - d);
        const VerifyReport across = MustVerify(seam, domain, d);
        EXPECT_FALSE(across.spacing_ok);
        EXPECT_LE(across.min_distance, 0.99 * d * (1 + 1e-9));
        EXPECT_TRUE(across.closest_index_a == static_cast<int64_t>(centre) ||
                    across.closest_index_b == static_cast<int64_t>(centre));
      }
    }
  }
}

// Far from the origin rounding is coarser: ulp(1e6 d) is about 1.2e-10 d, so
// the samplers' margin is 8 ulp(M), about 9e-10 d, and the verifier needs the
// tolerance its header prescribes there, (SpacingFor(d, M) - d) / d * 2.
TEST(SamplerMaximalityTest, FarFromTheOriginStillMaximal) {
  Rng dice(0x3d);
  for (const Config& config : kMaximalConfigs) {
    for (const bool torus : {false, true}) {
      const double d = dice.Uniform(0.5, 2.0);
      const double x0 = 1e6 * d + d * dice.Uniform(-20, 20);
      const double y0 = -1e6 * d + d * dice.Uniform(-20, 20);
      const Domain domain{{x0, y0, x0 + 16 * d, y0 + 12 * d}, torus};
      const uint64_t seed = dice.NextBits();
      SCOPED_TRACE(::testing::Message()
                   << Describe(config) << " seed " << seed << " torus " << torus);
      // M: the largest |coordinate| a sampler may touch (points and the 2 r'
      // margin around a rectangle).
      const double far_corner = std::max({std::abs(domain.rect.x0), std::abs(domain.rect.x1),
                                          std::abs(domain.rect.y0), std::abs(domain.rect.y1)});
      VerifyOptions verify_options;
      verify_options.max_tolerance = (SpacingFor(d, far_corner + 4 * d) - d) / d * 2;
      ASSERT_GT(verify_options.max_tolerance, 1e-9);  // else this test checks nothing new
      const std::vector<Vec2> points = MustSample(OptionsFor(config, domain, d, seed));
      ASSERT_GT(points.size(), 20u);
      const VerifyReport report = MustVerify(points, domain, d, verify_options);
      EXPECT_TRUE(report.spacing_ok) << report.min_distance / d;
      EXPECT_TRUE(report.maximal_ok) << report.largest_empty_circle / d - 1;
      EXPECT_EQ(report.points_outside, 0);
    }
  }
}

// KNOWN BUG, disabled until the geometry is fixed (enable it then): A1 and A2 can leave
// a hole a little wider than d. ScallopedRegion drops pieces whose area is below
// kNegligibleAreaFraction (1e-14) of the starting annulus, but area is quadratic in size: a
// three-disk gap whose spots are delta beyond every disk has area about 5 delta^2, so with
// r' = 2 d pieces up to delta ~ 1e-7 d are dropped, 100 times the verifier's tolerance and far
// above coordinate rounding. Seen on real output: A2, density 1.9772318930993729,
// d = 10.770575964600976, torus [9517.1781943304959, 9696.0426955934763) x
// [8745.5998799675817, 8988.8159639830592), seed 17363876358617396984 at commit d6a5a06 left an
// empty circle of 1 + 4.9e-8 d (1 run in about 3000 random A1/A2 runs of ~300 points).
// Here: a neighbourhood annulus (s, 2 d) minus three s-disks whose common gap is a spot 3e-8 d
// beyond each of them; the spot is available, so the neighbourhood must still contain it.
TEST(SamplerMaximalityTest, NeighbourhoodKeepsAGapWiderThanTheTolerance) {
  const double d = 1.0;
  const double s = SpacingFor(d, 4 * d);
  for (const double beyond : {1e-6, 1e-7, 3e-8}) {
    ScallopedRegion region = ScallopedRegion::Annulus({0.0, 0.0}, s, 2 * d);
    const Vec2 gap{1.9 * d, 0.0};
    for (int k = 0; k < 3; ++k) {
      region.SubtractDisk(gap + (s + beyond * d) * UnitAt(k * 2.0943951023931957), s);
    }
    EXPECT_TRUE(region.Contains(gap)) << "gap " << beyond << " d beyond three disks was dropped";
  }
}

}  // namespace
}  // namespace scallop
