// AvailableBoundary (A3's arc of a circle still free) against brute force:
// arc removal against a membership oracle over probe directions, keys and
// directions as inverses, and draws uniform by angle (chi-square), each
// check shown to catch a planted fault.
#include "scallop/sampling/available_boundary.h"

#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "scallop/random/rng.h"

namespace scallop {
namespace {

constexpr double kPi = std::numbers::pi;

// The direction at `angle` radians (libm is fine here: tests judge, they do not generate).
Vec2 At(double angle) { return {std::cos(angle), std::sin(angle)}; }

// Angle of a direction in [0, 2 pi).
double AngleOf(Vec2 v) {
  const double a = std::atan2(v.y, v.x);
  return a < 0 ? a + 2 * kPi : a;
}

// An arc as its end angles, counterclockwise from `from` to `to`.
struct AngleArc {
  double from, to;
};

// Whether `angle` lies on the closed arc (within `slack` of its ends counts as unknown: true).
bool OnArc(const AngleArc& arc, double angle, double slack) {
  const double width = std::fmod(arc.to - arc.from + 4 * kPi, 2 * kPi);
  const double offset = std::fmod(angle - arc.from + 4 * kPi, 2 * kPi);
  return offset <= width + slack || offset >= 2 * kPi - slack;
}

bool Available(const AvailableBoundary& boundary, double angle) {
  const double key = PseudoAngle(At(angle));
  for (const auto& range : boundary.ranges()) {
    if (range.begin < key && key < range.end) return true;
  }
  return false;
}

std::vector<AngleArc> RandomArcs(Rng& rng, int count) {
  std::vector<AngleArc> arcs;
  for (int i = 0; i < count; ++i) {
    const double from = rng.Uniform(0, 2 * kPi);
    // Mostly narrow arcs, as neighbours make, and some wide ones.
    const double width = rng.Uniform() < 0.8 ? rng.Uniform(0, 2.2) : rng.Uniform(0, 2 * kPi);
    arcs.push_back({from, from + width});
  }
  return arcs;
}

// Probes away from every arc end: there the oracle is exact whatever the
// rounding. Reports the first mismatch.
void ExpectMatchesOracle(const AvailableBoundary& boundary, const std::vector<AngleArc>& arcs,
                         Rng& rng, int probes) {
  constexpr double kSlack = 1e-9;
  for (int i = 0; i < probes; ++i) {
    const double angle = rng.Uniform(0, 2 * kPi);
    bool near_end = false, covered = false;
    for (const AngleArc& arc : arcs) {
      near_end = near_end || OnArc({arc.from, arc.from}, angle, kSlack) ||
                 OnArc({arc.to, arc.to}, angle, kSlack);
      covered = covered || OnArc(arc, angle, 0.0);
    }
    if (near_end || Available(boundary, angle) == !covered) continue;
    ADD_FAILURE() << "at angle " << angle << ": available " << !covered << " expected";
    return;
  }
}

TEST(AvailableBoundaryTest, SubtractArcMatchesAMembershipOracle) {
  for (uint64_t seed = 1; seed <= 300; ++seed) {
    Rng rng(seed);
    const std::vector<AngleArc> arcs = RandomArcs(rng, static_cast<int>(rng.Below(14)));
    AvailableBoundary boundary;
    boundary.Reset();
    for (const AngleArc& arc : arcs) boundary.SubtractArc(At(arc.from), At(arc.to));
    // Ranges stay sorted, disjoint and not empty.
    double previous_end = 0.0;
    for (const auto& range : boundary.ranges()) {
      EXPECT_LE(previous_end, range.begin);
      EXPECT_LT(range.begin, range.end);
      previous_end = range.end;
    }
    EXPECT_LE(previous_end, kFullTurnKey);
    ExpectMatchesOracle(boundary, arcs, rng, 400);
  }
}

TEST(AvailableBoundaryTest, OracleCatchesAPlantedMissingArc) {
  Rng rng(7);
  const std::vector<AngleArc> arcs = {{0.3, 1.1}, {2.0, 2.4}, {5.9, 6.6}};
  AvailableBoundary boundary;
  boundary.Reset();
  for (size_t k = 0; k + 1 < arcs.size(); ++k)
    boundary.SubtractArc(At(arcs[k].from), At(arcs[k].to));
  EXPECT_NONFATAL_FAILURE(ExpectMatchesOracle(boundary, arcs, rng, 400), "at angle");
}

TEST(AvailableBoundaryTest, SubtractingEverythingEmptiesIt) {
  AvailableBoundary boundary;
  boundary.Reset();
  EXPECT_FALSE(boundary.empty());
  boundary.SubtractArc(At(0.0), At(2.2));
  boundary.SubtractArc(At(2.1), At(4.3));
  EXPECT_FALSE(boundary.empty());
  boundary.SubtractArc(At(4.2), At(0.1));  // passes key 0
  EXPECT_TRUE(boundary.empty());
  boundary.Reset();
  boundary.Clear();
  EXPECT_TRUE(boundary.empty());
}

TEST(AvailableBoundaryTest, DirectionAtKeyInvertsPseudoAngle) {
  Rng rng(3);
  for (int i = 0; i < 100000; ++i) {
    const double key = rng.Uniform(0, kFullTurnKey);
    const Vec2 direction = DirectionAtKey(key);
    EXPECT_NEAR(std::abs(direction.x) + std::abs(direction.y), 1.0, 1e-15);
    EXPECT_NEAR(PseudoAngle(direction), key, 4e-16 * kFullTurnKey) << key;
  }
  // The quadrant ends, exactly.
  for (double key : {0.0, 1.0, 2.0, 3.0}) EXPECT_EQ(PseudoAngle(DirectionAtKey(key)), key);
  EXPECT_EQ(AngleOf(DirectionAtKey(kFullTurnKey)), 0.0);
}

// Chi-square of drawn angles over `bins` equal bins of [0, 2 pi) that lie
// wholly inside the available set (the others must get no draws at all).
double AngleChiSquare(const AvailableBoundary& boundary, Rng& rng, int bins, int draws,
                      int* bins_used) {
  std::vector<int> counts(bins, 0);
  std::vector<bool> inside(bins, true);
  for (int b = 0; b < bins; ++b) {
    for (int k = 0; k <= 8; ++k) {
      inside[b] = inside[b] && Available(boundary, 2 * kPi * (b + k / 8.0 * 0.999 + 0.0005) / bins);
    }
  }
  int total = 0;
  for (int i = 0; i < draws; ++i) {
    const AvailableBoundary::Draw draw = boundary.SampleDirection(rng);
    EXPECT_NEAR(PseudoAngle(draw.direction), draw.key, 2e-15);
    bool in_a_range = false;
    for (const auto& range : boundary.ranges()) {
      in_a_range = in_a_range || (range.begin <= draw.key && draw.key <= range.end);
    }
    EXPECT_TRUE(in_a_range) << draw.key;
    const int b = std::min(bins - 1, static_cast<int>(AngleOf(draw.direction) / (2 * kPi) * bins));
    if (inside[b]) {
      ++counts[b];
      ++total;
    }
  }
  *bins_used = 0;
  for (int b = 0; b < bins; ++b) *bins_used += inside[b];
  const double expected = static_cast<double>(total) / *bins_used;
  double chi_square = 0.0;
  for (int b = 0; b < bins; ++b) {
    if (inside[b]) chi_square += (counts[b] - expected) * (counts[b] - expected) / expected;
  }
  return chi_square;
}

// The chi-square bound for `dof` degrees of freedom at about p = 1e-4:
// dof + 3.7 sqrt(2 dof) (normal approximation, dof >= 50).
double ChiSquareLimit(int dof) { return dof + 3.7 * std::sqrt(2.0 * dof); }

TEST(AvailableBoundaryTest, DrawsAreUniformByAngle) {
  for (uint64_t seed = 1; seed <= 4; ++seed) {
    Rng rng(seed);
    AvailableBoundary boundary;
    boundary.Reset();
    for (uint64_t k = 1; k < seed; ++k) {  // seed 1: the whole circle; then pieces of it
      const double from = rng.Uniform(0, 2 * kPi);
      boundary.SubtractArc(At(from), At(from + rng.Uniform(0, 1.2)));
    }
    int bins_used = 0;
    const double chi_square = AngleChiSquare(boundary, rng, 240, 400000, &bins_used);
    ASSERT_GE(bins_used, 60);
    EXPECT_LT(chi_square, ChiSquareLimit(bins_used - 1)) << "seed " << seed;
  }
}

// The planted fault: keys drawn uniformly without the rejection step are
// uniform in pseudo-angle, not in angle (twice as dense near the diagonals).
TEST(AvailableBoundaryTest, ChiSquareCatchesDrawsUniformInKey) {
  Rng rng(5);
  constexpr int kBins = 240, kDraws = 400000;
  std::vector<int> counts(kBins, 0);
  for (int i = 0; i < kDraws; ++i) {
    const double angle = AngleOf(DirectionAtKey(rng.Uniform(0, kFullTurnKey)));
    ++counts[std::min(kBins - 1, static_cast<int>(angle / (2 * kPi) * kBins))];
  }
  const double expected = static_cast<double>(kDraws) / kBins;
  double chi_square = 0.0;
  for (int count : counts) chi_square += (count - expected) * (count - expected) / expected;
  EXPECT_GT(chi_square, ChiSquareLimit(kBins - 1));
}

}  // namespace
}  // namespace scallop
