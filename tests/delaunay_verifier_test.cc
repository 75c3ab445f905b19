// Tests of the Delaunay verifier against brute-force oracles (all pairs, and
// F1 probed on a dense grid), on known maximal sets, and on planted faults
// that each check must catch.
#include "scallop/verify/delaunay_verifier.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <limits>
#include <string>
#include <vector>

#include "scallop/random/rng.h"

namespace scallop {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

std::vector<Vec2> UniformPoints(Rng& rng, int count, const Rect& rect) {
  std::vector<Vec2> points;
  for (int i = 0; i < count; ++i) {
    points.push_back({rng.Uniform(rect.x0, rect.x1), rng.Uniform(rect.y0, rect.y1)});
  }
  return points;
}

// The minimum-image translates a torus pair can use, in the order a sampler
// might measure it: p against q + shift, or q against p - shift.
double TorusSquaredDistance(Vec2 p, Vec2 q, const Rect& rect) {
  double best = kInfinity;
  for (int sy = -1; sy <= 1; ++sy) {
    for (int sx = -1; sx <= 1; ++sx) {
      const Vec2 shift{sx * rect.Width(), sy * rect.Height()};
      best = std::min({best, SquaredDistance(p, q + shift), SquaredDistance(q, p - shift)});
    }
  }
  return best;
}

double PairSquaredDistance(Vec2 p, Vec2 q, const Domain& domain) {
  return domain.torus ? TorusSquaredDistance(p, q, domain.rect) : SquaredDistance(p, q);
}

// Dart throwing with an all-pairs check: spaced (at least d apart under the
// domain's metric), not maximal.
std::vector<Vec2> DartPoints(Rng& rng, int darts, const Domain& domain, double d) {
  std::vector<Vec2> points;
  for (int i = 0; i < darts; ++i) {
    const Vec2 p{rng.Uniform(domain.rect.x0, domain.rect.x1),
                 rng.Uniform(domain.rect.y0, domain.rect.y1)};
    bool far = true;
    for (const Vec2& q : points) far = far && PairSquaredDistance(p, q, domain) >= d * d;
    if (far) points.push_back(p);
  }
  return points;
}

// A hexagonal lattice of spacing s: rows s * sqrt(3) / 2 apart, odd rows
// shifted by s / 2, every lattice point of `rect` (half-open) taken, with each
// coordinate jittered by up to +-jitter.
std::vector<Vec2> HexLattice(double s, const Rect& rect, Rng* rng = nullptr, double jitter = 0.0) {
  const double row_height = s * std::sqrt(3.0) / 2.0;
  std::vector<Vec2> points;
  const int64_t first_row = static_cast<int64_t>(std::floor(rect.y0 / row_height)) - 1;
  const int64_t last_row = static_cast<int64_t>(std::ceil(rect.y1 / row_height)) + 1;
  for (int64_t row = first_row; row <= last_row; ++row) {
    const double offset = (row % 2 != 0) ? s / 2.0 : 0.0;
    const int64_t first = static_cast<int64_t>(std::floor(rect.x0 / s)) - 1;
    const int64_t last = static_cast<int64_t>(std::ceil(rect.x1 / s)) + 1;
    for (int64_t column = first; column <= last; ++column) {
      Vec2 p{static_cast<double>(column) * s + offset, static_cast<double>(row) * row_height};
      if (!rect.Contains(p)) continue;
      if (rng != nullptr) {
        // Clamped, not dropped, so the edges stay covered; the clamped point
        // stays within its jitter box, so the spacing bound holds.
        p = p + Vec2{rng->Uniform(-jitter, jitter), rng->Uniform(-jitter, jitter)};
        p.x = std::clamp(p.x, rect.x0, std::nextafter(rect.x1, rect.x0));
        p.y = std::clamp(p.y, rect.y0, std::nextafter(rect.y1, rect.y0));
      }
      points.push_back(p);
    }
  }
  return points;
}

// A hexagonal lattice of spacing s that tiles a torus of `columns` by
// 2 * row_pairs points exactly (its rectangle goes to `rect`); jittered points
// are wrapped back into the rectangle.
std::vector<Vec2> TorusLattice(double s, int columns, int row_pairs, Rect& rect, Rng* rng = nullptr,
                               double jitter = 0.0) {
  const double row_height = s * std::sqrt(3.0) / 2.0;
  rect = {0.0, 0.0, columns * s, 2 * row_pairs * row_height};
  std::vector<Vec2> points;
  for (int row = 0; row < 2 * row_pairs; ++row) {
    for (int column = 0; column < columns; ++column) {
      Vec2 p{column * s + (row % 2 != 0 ? s / 2.0 : 0.0), row * row_height};
      if (rng != nullptr)
        p = p + Vec2{rng->Uniform(-jitter, jitter), rng->Uniform(-jitter, jitter)};
      if (p.x < rect.x0) p.x += rect.Width();
      if (p.x >= rect.x1) p.x -= rect.Width();
      if (p.y < rect.y0) p.y += rect.Height();
      if (p.y >= rect.y1) p.y -= rect.Height();
      points.push_back(p);
    }
  }
  return points;
}

struct BruteSpacing {
  double min_distance = kInfinity;
  int64_t violations = 0;
};

BruteSpacing BruteForceSpacing(const std::vector<Vec2>& points, const Domain& domain, double d) {
  BruteSpacing result;
  for (size_t i = 0; i < points.size(); ++i) {
    for (size_t j = i + 1; j < points.size(); ++j) {
      const double squared = PairSquaredDistance(points[i], points[j], domain);
      result.min_distance = std::min(result.min_distance, std::sqrt(squared));
      result.violations += squared < d * d;
    }
  }
  return result;
}

// The largest F1 over a grid of step about `step` covering the closed area,
// both edges included. The true maximum is at most step / sqrt(2) above it.
double ProbeLargestEmptyCircle(const std::vector<Vec2>& points, const Rect& area, bool torus,
                               double step) {
  const int columns = static_cast<int>(std::ceil(area.Width() / step));
  const int rows = static_cast<int>(std::ceil(area.Height() / step));
  double best = 0.0;
  for (int r = 0; r <= rows; ++r) {
    const double y = r == rows ? area.y1 : area.y0 + area.Height() * r / rows;
    for (int c = 0; c <= columns; ++c) {
      const double x = c == columns ? area.x1 : area.x0 + area.Width() * c / columns;
      double nearest = kInfinity;
      for (const Vec2& p : points) {
        double dx = x - p.x, dy = y - p.y;
        if (torus) {
          dx -= area.Width() * std::round(dx / area.Width());
          dy -= area.Height() * std::round(dy / area.Height());
        }
        nearest = std::min(nearest, dx * dx + dy * dy);
      }
      best = std::max(best, std::sqrt(nearest));
    }
  }
  return best;
}

VerifyReport MustVerifyDomain(const std::vector<Vec2>& points, const Domain& domain, double d,
                              const VerifyOptions& options = {}) {
  StatusOr<VerifyReport> report = VerifyDomain(points, domain, d, options);
  EXPECT_TRUE(report.ok()) << report.status().message();
  return report.ok() ? *report : VerifyReport{};
}

VerifyReport MustVerifyWindow(const std::vector<Vec2>& points, const Rect& window, double d,
                              const VerifyOptions& options = {}) {
  StatusOr<VerifyReport> report = VerifyWindow(points, window, d, options);
  EXPECT_TRUE(report.ok()) << report.status().message();
  return report.ok() ? *report : VerifyReport{};
}

// Checks a report's spacing and empty circle against the oracles.
void ExpectMatchesBruteForce(const std::vector<Vec2>& points, const Domain& domain, double d,
                             double probe_step) {
  const VerifyReport report = MustVerifyDomain(points, domain, d);
  const BruteSpacing brute = BruteForceSpacing(points, domain, d);
  EXPECT_EQ(report.min_distance, brute.min_distance);
  EXPECT_LE(report.spacing_violations, brute.violations);
  EXPECT_EQ(report.spacing_violations == 0, brute.violations == 0);
  EXPECT_EQ(report.spacing_ok, brute.violations == 0);
  if (report.closest_index_a >= 0) {
    EXPECT_EQ(std::sqrt(PairSquaredDistance(points[report.closest_index_a],
                                            points[report.closest_index_b], domain)),
              report.min_distance);
  }
  const double probed = ProbeLargestEmptyCircle(points, domain.rect, domain.torus, probe_step);
  EXPECT_LE(probed, report.largest_empty_circle + 1e-9);
  EXPECT_LE(report.largest_empty_circle, probed + probe_step / std::sqrt(2.0) + 1e-9);
  // The reported centre is in the area and F1 there is the reported radius.
  const Rect& r = domain.rect;
  const Vec2 c = report.largest_empty_centre;
  EXPECT_TRUE(r.x0 <= c.x && c.x <= r.x1 && r.y0 <= c.y && c.y <= r.y1) << c.x << " " << c.y;
  double nearest = kInfinity;
  for (const Vec2& p : points) nearest = std::min(nearest, PairSquaredDistance(c, p, domain));
  EXPECT_NEAR(std::sqrt(nearest), report.largest_empty_circle, 1e-9);
}

TEST(DelaunayVerifierTest, MatchesBruteForceOnRandomSets) {
  const Rect rect{-3.0, 1.0, 7.0, 8.0};
  for (const bool torus : {false, true}) {
    for (uint64_t seed = 1; seed <= 8; ++seed) {
      SCOPED_TRACE("seed " + std::to_string(seed) + (torus ? " torus" : " rectangle"));
      Rng rng(seed);
      const Domain domain{rect, torus};
      // Uniform points: many violations and empty circles wider than 2 d,
      // which on a torus makes the replicated band widen.
      ExpectMatchesBruteForce(UniformPoints(rng, 200, rect), domain, 0.3, 0.04);
      // Spaced points: no violations, circles near d.
      ExpectMatchesBruteForce(DartPoints(rng, 400, domain, 0.6), domain, 0.6, 0.04);
    }
  }
}

TEST(DelaunayVerifierTest, MatchesBruteForceOnDegenerateSets) {
  const Rect rect{0.0, 0.0, 4.0, 3.0};
  for (const bool torus : {false, true}) {
    SCOPED_TRACE(torus ? "torus" : "rectangle");
    const Domain domain{rect, torus};
    ExpectMatchesBruteForce({{1.0, 1.0}}, domain, 0.5, 0.01);
    ExpectMatchesBruteForce({{1.0, 1.0}, {3.0, 2.5}}, domain, 0.5, 0.01);
    // Collinear, so the triangulation has no faces, horizontal and slanted.
    ExpectMatchesBruteForce({{0.0, 1.0}, {1.0, 1.0}, {2.5, 1.0}, {3.9, 1.0}}, domain, 0.5, 0.01);
    ExpectMatchesBruteForce({{0.5, 0.25}, {1.5, 0.75}, {2.5, 1.25}}, domain, 0.5, 0.01);
    // Cocircular: a square lattice, whose Voronoi edges have length zero.
    std::vector<Vec2> square;
    for (int x = 0; x < 4; ++x) {
      for (int y = 0; y < 3; ++y) square.push_back({x + 0.5, y + 0.5});
    }
    ExpectMatchesBruteForce(square, domain, 1.0, 0.01);
  }
}

TEST(DelaunayVerifierTest, EmptySetIsNotMaximal) {
  const VerifyReport report = MustVerifyDomain({}, Domain{{0, 0, 1, 1}, false}, 0.1);
  EXPECT_TRUE(report.spacing_ok);
  EXPECT_FALSE(report.maximal_ok);
  EXPECT_EQ(report.largest_empty_circle, kInfinity);
  EXPECT_EQ(report.pairs_checked, 0);
}

TEST(DelaunayVerifierTest, HexagonalLatticeOnTorusIsMaximal) {
  const double d = 0.7;
  // A hair over d, so rounding of the lattice coordinates cannot bring a pair
  // under d: the lattice is then exactly at the contract's edge.
  const double s = d * (1.0 + 1e-12);
  const int columns = 12, row_pairs = 7;
  Rect rect;
  const std::vector<Vec2> points = TorusLattice(s, columns, row_pairs, rect);
  ASSERT_EQ(points.size(), static_cast<size_t>(columns * 2 * row_pairs));
  const VerifyReport report = MustVerifyDomain(points, Domain{rect, true}, d);
  EXPECT_TRUE(report.passed());
  EXPECT_EQ(report.points_checked, static_cast<int64_t>(points.size()));
  EXPECT_NEAR(report.min_distance, s, 1e-12);
  EXPECT_NEAR(report.largest_empty_circle, s / std::sqrt(3.0), 1e-12);
  // Every lattice point has six neighbours, and a torus pair counts once.
  EXPECT_EQ(report.pairs_checked, static_cast<int64_t>(3 * points.size()));
}

// A rectangle that cuts the lattice between rows and columns, so that its
// boundary is covered as well as its inside.
Rect CoveredRectangle(double s, int columns, int rows) {
  const double row_height = s * std::sqrt(3.0) / 2.0;
  return {0.0, 0.0, (columns - 0.25) * s, (rows - 0.5) * row_height};
}

TEST(DelaunayVerifierTest, HexagonalLatticeOnRectangleIsMaximal) {
  const double d = 1.0, s = d * (1.0 + 1e-12);
  const Rect rect = CoveredRectangle(s, 20, 24);
  const std::vector<Vec2> points = HexLattice(s, rect);
  const VerifyReport report = MustVerifyDomain(points, Domain{rect, false}, d);
  EXPECT_TRUE(report.passed());
  EXPECT_GE(report.largest_empty_circle, s / std::sqrt(3.0) - 1e-12);
  EXPECT_LT(report.largest_empty_circle, 0.8 * d);
}

TEST(DelaunayVerifierTest, PointsExactlyDApartAreNoViolation) {
  // 3-4-5: dx^2 + dy^2 == 25 exactly in double precision.
  const std::vector<Vec2> points{{0.0, 0.0}, {3.0, 4.0}, {8.0, 4.0}};
  const Domain domain{{-1.0, -1.0, 10.0, 6.0}, false};
  VerifyReport report = MustVerifyDomain(points, domain, 5.0);
  EXPECT_EQ(report.spacing_violations, 0);
  EXPECT_EQ(report.min_distance, 5.0);
  report = MustVerifyDomain(points, domain, std::nextafter(5.0, 6.0));
  EXPECT_EQ(report.spacing_violations, 2);
  EXPECT_FALSE(report.spacing_ok);
}

TEST(DelaunayVerifierTest, CoincidentPointsAreTheWorstViolation) {
  const std::vector<Vec2> points{{0.5, 0.5}, {2.0, 2.0}, {0.5, 0.5}};
  const VerifyReport report = MustVerifyDomain(points, Domain{{0, 0, 3, 3}, false}, 1.0);
  EXPECT_EQ(report.min_distance, 0.0);
  EXPECT_EQ(report.spacing_violations, 1);
  EXPECT_EQ(std::min(report.closest_index_a, report.closest_index_b), 0);
  EXPECT_EQ(std::max(report.closest_index_a, report.closest_index_b), 2);
}

// A maximal set with room to spare: a lattice of spacing 1.1 d jittered by up
// to 0.03 d per coordinate keeps pairs above 1.01 d and empty circles under
// 0.9 d, so removing a point leaves a hole wider than d.
std::vector<Vec2> SpareMaximalSet(Rng& rng, const Rect& rect, double d) {
  return HexLattice(1.1 * d, rect, &rng, 0.03 * d);
}

TEST(DelaunayVerifierTest, CatchesPlantedFaults) {
  const double d = 1.0;
  const Rect rect = CoveredRectangle(1.1 * d, 30, 30);
  const Domain domain{rect, false};
  for (uint64_t seed = 100; seed < 110; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    Rng rng(seed);
    const std::vector<Vec2> points = SpareMaximalSet(rng, rect, d);
    ASSERT_TRUE(MustVerifyDomain(points, domain, d).passed());

    // A removed point leaves a hole centred near it.
    const size_t removed = rng.Below(points.size());
    std::vector<Vec2> holed = points;
    holed.erase(holed.begin() + static_cast<int64_t>(removed));
    VerifyReport report = MustVerifyDomain(holed, domain, d);
    EXPECT_TRUE(report.spacing_ok);
    EXPECT_FALSE(report.maximal_ok);
    EXPECT_GT(report.largest_empty_circle, d);
    EXPECT_LT(Length(report.largest_empty_centre - points[removed]), 0.2 * d);

    // A point slid towards its nearest neighbour until 0.99 d from it.
    const size_t moved = rng.Below(points.size());
    size_t other = moved == 0 ? 1 : 0;
    for (size_t k = 0; k < points.size(); ++k) {
      if (k != moved && SquaredDistance(points[k], points[moved]) <
                            SquaredDistance(points[other], points[moved])) {
        other = k;
      }
    }
    const Vec2 away = points[moved] - points[other];
    std::vector<Vec2> crowded = points;
    crowded[moved] = points[other] + (0.99 * d / Length(away)) * away;
    report = MustVerifyDomain(crowded, domain, d);
    EXPECT_FALSE(report.spacing_ok);
    EXPECT_GE(report.spacing_violations, 1);
    EXPECT_NEAR(report.min_distance, 0.99 * d, 1e-12);
    EXPECT_EQ(std::min(report.closest_index_a, report.closest_index_b),
              static_cast<int64_t>(std::min(moved, other)));
  }
}

TEST(DelaunayVerifierTest, CatchesUncoveredCorner) {
  const double d = 1.0;
  const Rect rect = CoveredRectangle(1.1 * d, 20, 20);
  Rng rng(7);
  std::vector<Vec2> points = SpareMaximalSet(rng, rect, d);
  // Every point within 1.5 d of the top right corner removed.
  const Vec2 corner{rect.x1, rect.y1};
  std::erase_if(points, [&](Vec2 p) { return Length(p - corner) < 1.5 * d; });
  const VerifyReport report = MustVerifyDomain(points, Domain{rect, false}, d);
  EXPECT_TRUE(report.spacing_ok);
  EXPECT_FALSE(report.maximal_ok);
  EXPECT_GE(report.largest_empty_circle, 1.5 * d);
  EXPECT_EQ(report.largest_empty_centre, corner);
}

TEST(DelaunayVerifierTest, CountsPointsOutsideTheRectangle) {
  const Rect rect{0.0, 0.0, 2.0, 2.0};
  // The far edges belong to the neighbouring rectangle.
  const std::vector<Vec2> points{{0.0, 0.0}, {2.0, 1.0}, {1.0, 2.0}, {1.0, 1.0}};
  const VerifyReport report = MustVerifyDomain(points, Domain{rect, false}, 0.5);
  EXPECT_EQ(report.points_checked, 2);
  EXPECT_EQ(report.points_outside, 2);
  EXPECT_FALSE(report.passed());
}

TEST(DelaunayVerifierTest, TorusMeasuresAcrossTheWrap) {
  const Rect rect{0.0, 0.0, 10.0, 10.0};
  // 0.4 apart through the left/right edge, 9.6 apart inside.
  const std::vector<Vec2> points{{0.1, 5.0}, {9.7, 5.0}};
  VerifyReport report = MustVerifyDomain(points, Domain{rect, true}, 1.0);
  EXPECT_EQ(report.spacing_violations, 1);
  EXPECT_NEAR(report.min_distance, 0.4, 1e-12);
  report = MustVerifyDomain(points, Domain{rect, false}, 1.0);
  EXPECT_EQ(report.spacing_violations, 0);
  EXPECT_NEAR(report.min_distance, 9.6, 1e-12);
}

TEST(DelaunayVerifierTest, WindowJudgesOnlyTheWindow) {
  const double d = 1.0;
  const Rect window{0.0, 0.0, 20.0, 20.0};
  const Rect covered{-5.0, -5.0, 25.0, 25.0};
  Rng rng(11);
  const std::vector<Vec2> points = SpareMaximalSet(rng, covered, d);
  VerifyReport report = MustVerifyWindow(points, window, d);
  EXPECT_TRUE(report.passed());
  EXPECT_GT(report.points_checked, 300);
  EXPECT_LT(report.points_checked, static_cast<int64_t>(points.size()));

  const auto without_near = [&](Vec2 spot, double radius) {
    std::vector<Vec2> holed = points;
    std::erase_if(holed, [&](Vec2 p) { return Length(p - spot) < radius; });
    return holed;
  };
  // A hole whose empty circles are all centred outside the window.
  report = MustVerifyWindow(without_near({23.0, 10.0}, 1.2 * d), window, d);
  EXPECT_TRUE(report.maximal_ok) << report.largest_empty_circle;
  // A hole inside.
  report = MustVerifyWindow(without_near({10.0, 10.0}, 1.2 * d), window, d);
  EXPECT_FALSE(report.maximal_ok);
  EXPECT_LT(Length(report.largest_empty_centre - Vec2{10.0, 10.0}), 0.5 * d);

  // A crowded pair outside is ignored; one with an end inside is not.
  std::vector<Vec2> crowded = points;
  crowded.push_back({-3.0, 10.0});
  crowded.push_back({-3.0 + 0.2 * d, 10.0});
  EXPECT_TRUE(MustVerifyWindow(crowded, window, d).spacing_ok);
  crowded.push_back({19.95, 10.3});
  crowded.push_back({20.05, 10.3});
  report = MustVerifyWindow(crowded, window, d);
  EXPECT_FALSE(report.spacing_ok);
  EXPECT_NEAR(report.min_distance, 0.1, 1e-9);
}

TEST(DelaunayVerifierTest, WindowMatchesBruteForceEmptyCircle) {
  const double d = 0.5;
  const Rect window{0.0, 0.0, 5.0, 4.0};
  const Rect covered{-2 * d, -2 * d, 5.0 + 2 * d, 4.0 + 2 * d};
  for (uint64_t seed = 200; seed < 210; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    Rng rng(seed);
    const std::vector<Vec2> points = DartPoints(rng, 300, Domain{covered, false}, d);
    const VerifyReport report = MustVerifyWindow(points, window, d);
    const double step = 0.01;
    const double probed = ProbeLargestEmptyCircle(points, window, false, step);
    EXPECT_LE(probed, report.largest_empty_circle + 1e-9);
    EXPECT_LE(report.largest_empty_circle, probed + step / std::sqrt(2.0) + 1e-9);
  }
}

TEST(DelaunayVerifierTest, CountsPairsAcrossSeams) {
  const double d = 0.5, seam = 2.0;
  const Rect window{0.0, 0.0, 8.0, 8.0};
  for (uint64_t seed = 300; seed < 306; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    Rng rng(seed);
    // Each region filled on its own, as a careless tiling would: violations
    // can only be across seams.
    std::vector<Vec2> points;
    for (int ry = 0; ry < 4; ++ry) {
      for (int rx = 0; rx < 4; ++rx) {
        const Rect region{rx * seam, ry * seam, (rx + 1) * seam, (ry + 1) * seam};
        const std::vector<Vec2> part = DartPoints(rng, 80, Domain{region, false}, d);
        points.insert(points.end(), part.begin(), part.end());
      }
    }
    VerifyOptions options;
    options.seam_spacing = seam;
    const VerifyReport report = MustVerifyWindow(points, window, d, options);
    double brute_min_across = kInfinity;
    int64_t brute_violations_across = 0;
    for (size_t i = 0; i < points.size(); ++i) {
      for (size_t j = i + 1; j < points.size(); ++j) {
        const Vec2 a = points[i], b = points[j];
        if (std::floor(a.x / seam) == std::floor(b.x / seam) &&
            std::floor(a.y / seam) == std::floor(b.y / seam)) {
          continue;
        }
        const double squared = SquaredDistance(a, b);
        brute_min_across = std::min(brute_min_across, std::sqrt(squared));
        brute_violations_across += squared < d * d;
      }
    }
    EXPECT_EQ(report.min_distance_across_seams, brute_min_across);
    EXPECT_GT(brute_violations_across, 0);
    EXPECT_EQ(report.spacing_violations_across_seams, report.spacing_violations);
    EXPECT_GT(report.spacing_violations_across_seams, 0);
    EXPECT_LE(report.spacing_violations_across_seams, brute_violations_across);
    EXPECT_GT(report.pairs_across_seams, 0);
    EXPECT_LT(report.pairs_across_seams, report.pairs_checked);
    // Without seams nothing is counted across them.
    EXPECT_EQ(MustVerifyWindow(points, window, d).pairs_across_seams, 0);
  }
}

TEST(DelaunayVerifierTest, RejectsBadInput) {
  const std::vector<Vec2> points{{0.5, 0.5}};
  const Domain domain{{0, 0, 1, 1}, false};
  EXPECT_FALSE(VerifyDomain(points, domain, 0.0).ok());
  EXPECT_FALSE(VerifyDomain(points, domain, std::nan("")).ok());
  EXPECT_FALSE(VerifyDomain(points, Domain{{1, 0, 0, 1}, false}, 0.1).ok());
  EXPECT_FALSE(VerifyDomain(points, Domain{{0, 0, kInfinity, 1}, true}, 0.1).ok());
  const std::vector<Vec2> bad{{0.5, 0.5}, {std::nan(""), 0.5}};
  const StatusOr<VerifyReport> report = VerifyWindow(bad, domain.rect, 0.1);
  ASSERT_FALSE(report.ok());
  EXPECT_NE(report.status().message().find("points[1]"), std::string::npos);
  VerifyOptions options;
  options.seam_spacing = -1.0;
  EXPECT_FALSE(VerifyWindow(points, domain.rect, 0.1, options).ok());
}

// options.stop (issue 20: a Verify whose client has gone stops): polled as
// documented, a stop that never fires changes nothing, and one that fires
// ends the run with CANCELLED, in the insertion and in the scans.
TEST(DelaunayVerifierTest, StopIsPolledAndEndsTheRunWithCancelled) {
  Rng rng(20);
  const double d = 1.0;
  const Rect rect = CoveredRectangle(1.1 * d, 200, 230);  // about 46,000 points
  const std::vector<Vec2> points = SpareMaximalSet(rng, rect, d);
  const VerifyReport plain = MustVerifyDomain(points, Domain{rect, false}, d);
  int polls = 0;
  VerifyOptions never;
  never.stop = [&] { return ++polls < 0; };
  const StatusOr<VerifyReport> polled = VerifyWindow(points, rect, d, never);
  ASSERT_TRUE(polled.ok());
  // One poll per 16,384 of the ~46,000 insertions, ~92,000 faces and ~138,000 edges.
  EXPECT_GE(polls, 15);
  EXPECT_LE(polls, 18);
  const StatusOr<VerifyReport> unpolled = VerifyWindow(points, rect, d);
  ASSERT_TRUE(unpolled.ok());
  EXPECT_EQ(polled->largest_empty_circle, unpolled->largest_empty_circle);
  EXPECT_EQ(polled->pairs_checked, unpolled->pairs_checked);
  EXPECT_TRUE(plain.passed());
  // Stopping at the k-th poll, for a poll in each phase.
  for (const int stop_at : {1, 6, 12}) {
    int calls = 0;
    VerifyOptions stopping;
    stopping.stop = [&] { return ++calls >= stop_at; };
    const StatusOr<VerifyReport> stopped = VerifyDomain(points, Domain{rect, false}, d, stopping);
    ASSERT_FALSE(stopped.ok()) << stop_at;
    EXPECT_EQ(stopped.status().code(), StatusCode::kCancelled);
    EXPECT_EQ(calls, stop_at);
  }
}

// About a million spaced random points (jittered lattices) on a rectangle, a
// torus and a window: checks they pass and prints the times.
TEST(DelaunayVerifierTest, MillionPoints) {
  const double d = 1.0;
  Rng rng(1'000'000);
  const auto timed = [](const char* what, size_t count, auto verify) {
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    const VerifyReport report = verify();
    const double cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%s: %zu points in %.3f s (%.3f s CPU), min distance %.6f, largest circle %.6f\n",
                what, count, seconds, cpu_seconds, report.min_distance,
                report.largest_empty_circle);
    EXPECT_TRUE(report.passed()) << what;
  };
  const Rect rect = CoveredRectangle(1.1 * d, 1000, 1150);
  const std::vector<Vec2> points = SpareMaximalSet(rng, rect, d);
  timed("VerifyDomain rectangle", points.size(), [&] {
    return MustVerifyDomain(points, Domain{rect, false}, d);
  });
  const Rect window{rect.x0 + 2.5, rect.y0 + 2.5, rect.x1 - 2.5, rect.y1 - 2.5};
  timed("VerifyWindow", points.size(), [&] { return MustVerifyWindow(points, window, d); });
  Rect torus_rect;
  const std::vector<Vec2> torus_points = TorusLattice(1.1 * d, 1000, 575, torus_rect, &rng, 0.03);
  timed("VerifyDomain torus", torus_points.size(), [&] {
    return MustVerifyDomain(torus_points, Domain{torus_rect, true}, d);
  });
}

}  // namespace
}  // namespace scallop
