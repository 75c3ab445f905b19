// Tests of the point statistics: the normalised radius on the hexagonal
// lattice, the pair histogram against all pairs, and g(r) of uniform points.
#include "scallop/analysis/point_statistics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "scallop/random/rng.h"

namespace scallop {
namespace {

std::vector<Vec2> UniformPoints(Rng& rng, int count, const Rect& rect) {
  std::vector<Vec2> points;
  for (int i = 0; i < count; ++i) {
    points.push_back({rng.Uniform(rect.x0, rect.x1), rng.Uniform(rect.y0, rect.y1)});
  }
  return points;
}

// The same bins by all pairs, measured exactly as the histogram measures them.
std::vector<int64_t> BruteForceCounts(const std::vector<Vec2>& points, const Domain& domain,
                                      double max_distance, int bin_count) {
  std::vector<int64_t> counts(static_cast<size_t>(bin_count), 0);
  const double bin_width = max_distance / bin_count;
  const double width = domain.rect.Width(), height = domain.rect.Height();
  for (size_t i = 0; i < points.size(); ++i) {
    for (size_t j = i + 1; j < points.size(); ++j) {
      double dx = points[i].x - points[j].x, dy = points[i].y - points[j].y;
      if (domain.torus) {
        dx -= width * std::round(dx / width);
        dy -= height * std::round(dy / height);
      }
      const double squared = dx * dx + dy * dy;
      if (squared >= max_distance * max_distance) continue;
      ++counts[static_cast<size_t>(
          std::min(static_cast<int>(std::sqrt(squared) / bin_width), bin_count - 1))];
    }
  }
  return counts;
}

TEST(PointStatisticsTest, HexagonalLatticeHasNormalisedRadiusOne) {
  for (const double d : {1.0, 0.37, 12.5}) {
    const int columns = 40, rows = 30;  // rows d * sqrt(3) / 2 apart
    const double area = (columns * d) * (rows * d * std::sqrt(3.0) / 2.0);
    const StatusOr<double> radius = NormalisedRadius(columns * rows, area, d);
    ASSERT_TRUE(radius.ok());
    EXPECT_NEAR(*radius, 1.0, 1e-14) << "d " << d;
  }
  // Half the density: the lattice spacing grows by sqrt(2).
  EXPECT_NEAR(*NormalisedRadius(600, 1200 * std::sqrt(3.0) / 2.0, 1.0), 1.0 / std::sqrt(2.0),
              1e-14);
}

TEST(PointStatisticsTest, NormalisedRadiusRejectsBadInput) {
  EXPECT_FALSE(NormalisedRadius(0, 1.0, 1.0).ok());
  EXPECT_FALSE(NormalisedRadius(10, 0.0, 1.0).ok());
  EXPECT_FALSE(NormalisedRadius(10, 1.0, -1.0).ok());
  EXPECT_FALSE(NormalisedRadius(10, std::nan(""), 1.0).ok());
}

TEST(PointStatisticsTest, HistogramMatchesBruteForce) {
  const Rect rect{-2.0, 3.0, 9.0, 10.0};
  for (const bool torus : {false, true}) {
    for (uint64_t seed = 1; seed <= 10; ++seed) {
      SCOPED_TRACE("seed " + std::to_string(seed) + (torus ? " torus" : " rectangle"));
      Rng rng(seed);
      const Domain domain{rect, torus};
      const std::vector<Vec2> points = UniformPoints(rng, 300, rect);
      // A short reach (many cells), and the longest allowed (one or two cells
      // per side, where a torus's neighbours wrap onto each other).
      for (const double reach : {0.8, torus ? 3.5 : 7.0}) {
        const int bins = 17;
        const StatusOr<PairDistanceHistogram> histogram =
            HistogramPairDistances(points, domain, reach, bins);
        ASSERT_TRUE(histogram.ok()) << histogram.status().message();
        EXPECT_EQ(histogram->pair_counts, BruteForceCounts(points, domain, reach, bins))
            << "reach " << reach;
        EXPECT_EQ(histogram->radial_distribution.size(), static_cast<size_t>(bins));
      }
    }
  }
}

TEST(PointStatisticsTest, UniformPointsHaveFlatRadialDistribution) {
  const Rect rect{0.0, 0.0, 100.0, 80.0};
  for (const bool torus : {false, true}) {
    SCOPED_TRACE(torus ? "torus" : "rectangle");
    Rng rng(torus ? 42 : 43);
    const std::vector<Vec2> points = UniformPoints(rng, 20000, rect);
    const StatusOr<PairDistanceHistogram> histogram =
        HistogramPairDistances(points, Domain{rect, torus}, 5.0, 10);
    ASSERT_TRUE(histogram.ok());
    // The fewest expected pairs, in the first bin, are about 15000: a
    // standard deviation under 1 %, so 5 % never flakes.
    for (size_t k = 0; k < histogram->radial_distribution.size(); ++k) {
      EXPECT_NEAR(histogram->radial_distribution[k], 1.0, 0.05) << "bin " << k;
    }
  }
}

TEST(PointStatisticsTest, SpacedPointsHaveNoPairsBelowD) {
  const Rect rect{0.0, 0.0, 20.0, 20.0};
  const double d = 1.0;
  Rng rng(5);
  std::vector<Vec2> points;
  for (int dart = 0; dart < 5000; ++dart) {
    const Vec2 p{rng.Uniform(rect.x0, rect.x1), rng.Uniform(rect.y0, rect.y1)};
    if (std::all_of(points.begin(), points.end(),
                    [&](Vec2 q) { return SquaredDistance(p, q) >= d * d; })) {
      points.push_back(p);
    }
  }
  const StatusOr<PairDistanceHistogram> histogram =
      HistogramPairDistances(points, Domain{rect, false}, 3.0, 30);
  ASSERT_TRUE(histogram.ok());
  for (int k = 0; k < 10; ++k) {
    EXPECT_EQ(histogram->pair_counts[k], 0) << "bin " << k;
    EXPECT_EQ(histogram->radial_distribution[k], 0.0);
  }
  // The first shell past d is crowded: dart throwing piles pairs up there.
  EXPECT_GT(histogram->radial_distribution[10], 1.0);
}

TEST(PointStatisticsTest, HistogramRejectsBadInput) {
  const Domain domain{{0.0, 0.0, 10.0, 4.0}, true};
  const std::vector<Vec2> points{{1.0, 1.0}, {2.0, 2.0}};
  EXPECT_FALSE(HistogramPairDistances(points, domain, 0.0, 10).ok());
  EXPECT_FALSE(HistogramPairDistances(points, domain, 2.5, 10).ok());  // over half a side
  EXPECT_TRUE(HistogramPairDistances(points, Domain{domain.rect, false}, 2.5, 10).ok());
  EXPECT_FALSE(HistogramPairDistances(points, domain, 1.0, 0).ok());
  EXPECT_FALSE(HistogramPairDistances(points, Domain{{0, 0, -1, 1}, false}, 0.5, 10).ok());
  const std::vector<Vec2> outside{{1.0, 1.0}, {10.0, 2.0}};
  const StatusOr<PairDistanceHistogram> rejected = HistogramPairDistances(outside, domain, 1, 10);
  ASSERT_FALSE(rejected.ok());
  EXPECT_NE(rejected.status().message().find("points[1]"), std::string::npos);
  // No points: empty counts, g of zero.
  const StatusOr<PairDistanceHistogram> empty = HistogramPairDistances({}, domain, 1.0, 4);
  ASSERT_TRUE(empty.ok());
  EXPECT_EQ(empty->pair_counts, std::vector<int64_t>(4, 0));
  EXPECT_EQ(empty->radial_distribution, std::vector<double>(4, 0.0));
}

}  // namespace
}  // namespace scallop
