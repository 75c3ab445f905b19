// The field growth's arcs (curve_arcs.h) against brute force: for random circles, disks and
// lines, every direction a cut removes is one whose spot lies in the disk (beyond the line), and
// every direction it keeps is one whose spot does not, except within a hair of an arc's end.
#include "scallop/sampling/curve_arcs.h"

#include <gtest/gtest.h>

#include <cmath>

#include "scallop/random/rng.h"

namespace scallop {
namespace {

constexpr double kTwoPi = 6.283185307179586;

// Whether `key` is still available in the boundary.
bool Available(const AvailableBoundary& boundary, double key) {
  for (const AvailableBoundary::Range& r : boundary.ranges()) {
    if (r.begin < key && key < r.end) return true;
  }
  return false;
}

// Counts directions (of 720 about the circle) that the cut classifies against `inside`, which
// says whether the spot t u is refused; directions within `hair` radians of a change of `inside`
// are skipped, where rounding decides.
template <typename Inside>
int64_t Misclassified(const AvailableBoundary& boundary, Inside inside, double hair) {
  int64_t wrong = 0;
  for (int k = 0; k < 720; ++k) {
    const double angle = kTwoPi * (k + 0.5) / 720.0;
    const Vec2 u = UnitAt(angle);
    const bool in = inside(u);
    if (inside(UnitAt(angle - hair)) != in || inside(UnitAt(angle + hair)) != in) continue;
    if (Available(boundary, PseudoAngle(u)) == in) ++wrong;
  }
  return wrong;
}

TEST(CurveArcsTest, DiskArcRemovesExactlyTheDirectionsInsideTheDisk) {
  int64_t wrong = 0;
  int kinds[3] = {0, 0, 0};
  for (uint64_t seed = 1; seed <= 400; ++seed) {
    Rng rng(HashWords({seed, 0x61726373}));
    const double t = rng.Uniform(0.5, 4.0);
    const Vec2 offset = rng.Uniform(0.0, 3.0 * t) * UnitAt(kTwoPi * rng.Uniform());
    const double m = rng.Uniform(0.1, 3.0 * t);
    AvailableBoundary boundary;
    boundary.Reset();
    KeyArc arc;
    const ArcCut cut = DiskArc(offset, t, m, &arc);
    ++kinds[static_cast<int>(cut)];
    Cut(boundary, cut, arc);
    wrong += Misclassified(
        boundary, [&](Vec2 u) { return SquaredDistance(t * u, offset) < m * m; }, 1e-9);
  }
  EXPECT_EQ(wrong, 0);
  // The seeds reach all three outcomes.
  EXPECT_GT(kinds[0], 0);
  EXPECT_GT(kinds[1], 0);
  EXPECT_GT(kinds[2], 0);
}

TEST(CurveArcsTest, BeyondLineArcRemovesExactlyTheDirectionsBeyondTheLine) {
  int64_t wrong = 0;
  for (uint64_t seed = 1; seed <= 400; ++seed) {
    Rng rng(HashWords({seed, 0x6c696e65}));
    const double t = rng.Uniform(0.5, 4.0);
    const Vec2 normal = UnitAt(kTwoPi * rng.Uniform());
    const double distance = rng.Uniform(-1.2 * t, 1.2 * t);
    AvailableBoundary boundary;
    boundary.Reset();
    KeyArc arc;
    Cut(boundary, BeyondLineArc(normal, distance, t, &arc), arc);
    wrong += Misclassified(
        boundary, [&](Vec2 u) { return t * Dot(u, normal) >= distance; }, 1e-9);
  }
  EXPECT_EQ(wrong, 0);
}

TEST(CurveArcsTest, CutAroundKeyWrapsAtAWholeTurn) {
  for (const double key : {0.001, 1.5, 3.999}) {
    AvailableBoundary boundary;
    boundary.Reset();
    CutAroundKey(boundary, key, 0.01);
    EXPECT_FALSE(Available(boundary, key));
    EXPECT_FALSE(Available(boundary, std::fmod(key + 0.009, kFullTurnKey)));
    EXPECT_FALSE(Available(boundary, std::fmod(key - 0.009 + kFullTurnKey, kFullTurnKey)));
    EXPECT_TRUE(Available(boundary, std::fmod(key + 0.011, kFullTurnKey)));
    EXPECT_TRUE(Available(boundary, std::fmod(key - 0.011 + kFullTurnKey, kFullTurnKey)));
  }
}

// A planted fault: an arc whose ends are swapped (the complement) is caught.
TEST(CurveArcsTest, SwappedEndsAreCaught) {
  const Vec2 offset{1.5, 0.5};
  const double t = 1.0;
  const double m = 1.0;
  KeyArc arc;
  ASSERT_EQ(DiskArc(offset, t, m, &arc), ArcCut::kArc);
  AvailableBoundary boundary;
  boundary.Reset();
  boundary.SubtractArc(arc.to_key, arc.from_key);
  EXPECT_GT(Misclassified(
                boundary, [&](Vec2 u) { return SquaredDistance(t * u, offset) < m * m; }, 1e-9),
            100);
}

}  // namespace
}  // namespace scallop
