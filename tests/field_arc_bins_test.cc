// The field growth's arc bins (field_arc_bins.h, field_candidate_boundary.h) against brute
// force: the bins looked up for a neighbour hold for the keys DiskArc computes, at any circle
// radius, for ratios m / t at and between the tables' bounds, near tangency and at the cells'
// bounds; a boundary built by bins is, to the bit, the boundary of cutting every arc. Each check
// is shown to catch a planted fault.
#include "scallop/sampling/field_arc_bins.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <numbers>
#include <vector>

#include "scallop/random/rng.h"
#include "scallop/sampling/arc_bins.h"
#include "scallop/sampling/curve_arcs.h"
#include "scallop/sampling/field_candidate_boundary.h"
#include "tests/arc_bin_checks.h"

namespace scallop {
namespace {

using arc_bin_checks::BinErrors;
using arc_bin_checks::SameRanges;

// A ratio m / t: often exactly 1 (a neighbour with a smaller R), at a table's bound or a hair
// either side of it, else uniform up to a little beyond the last table.
double AwkwardRatio(Rng& rng) {
  const double u = rng.Uniform();
  if (u < 0.3) return 1.0;
  if (u < 0.5) {
    const double bound = 1.0 + static_cast<double>(rng.Below(5)) / FieldArcBins::kStepsPerUnit;
    const int side = static_cast<int>(rng.Below(3));
    return side == 0 ? bound : std::nextafter(bound, side == 1 ? 0.0 : 4.0);
  }
  return rng.Uniform(1.0, FieldArcBins::kMaxRatio + 0.2);
}

// An offset (in units of t) within 1 + ratio: uniform by length, and often at the tables' cell
// bounds, on the axes, near the outer tangency (1 + ratio) or the inner one (ratio - 1).
Vec2 AwkwardOffset(Rng& rng, double ratio) {
  const double outer = 1.0 + ratio;
  const double u = rng.Uniform();
  if (u < 0.15) {
    const Vec2 o = {static_cast<double>(rng.Below(97)) / 16 - 3,
                    static_cast<double>(rng.Below(97)) / 16 - 3};
    if (SquaredLength(o) < outer * outer && SquaredLength(o) > 0) return o;
  }
  const double angle = u < 0.25 ? rng.Below(8) * std::numbers::pi / 4 : rng.Uniform(0, 7);
  double length = rng.Uniform(1e-3, outer);
  if (u > 0.75) length = outer * (1 - std::pow(10.0, -rng.Uniform(1, 15)));
  if (u > 0.9) length = (ratio - 1.0) + rng.Uniform(-1e-9, 1e-9);
  if (!(length > 0.0)) length = 1e-6;
  return {length * std::cos(angle), length * std::sin(angle)};
}

// Checks FieldArcBins::Of against DiskArc for random neighbours; `plant` turns a fault into the
// looked-up bins first. Returns how many neighbours got wrong bins; counts the bins it covers.
long WrongBins(Rng& rng, int trials, bool plant, long* covered_bins, long* exact_arcs) {
  long wrong = 0;
  for (const double t : {1.0, 1e-3, 7.3, 3e4}) {
    const FieldArcBins bins(t);
    for (int trial = 0; trial < trials; ++trial) {
      const double ratio = AwkwardRatio(rng);
      const double m = ratio == 1.0 ? t : t * ratio;
      const Vec2 unit = AwkwardOffset(rng, m / t);
      const Vec2 offset = {unit.x * t, unit.y * t};
      if (!(SquaredLength(offset) < (t + m) * (t + m))) continue;  // Of's REQUIRES
      ArcBins looked_up = bins.Of(offset, m / t);
      if (plant) looked_up.covered |= std::rotl(looked_up.covered, 1);
      KeyArc arc{0, 0};
      const ArcCut cut = DiskArc(offset, t, m, &arc);
      bool right = true;
      if (cut == ArcCut::kNone) right = looked_up.covered == 0;
      if (cut == ArcCut::kWhole) right = looked_up.reached == ~uint64_t{0};
      if (cut == ArcCut::kArc) right = BinErrors(arc, looked_up) == 0;
      wrong += right ? 0 : 1;
      *covered_bins += std::popcount(looked_up.covered);
      *exact_arcs += 1;
    }
  }
  return wrong;
}

TEST(FieldArcBinsTest, BinsHoldForTheArcsDiskArcComputes) {
  Rng rng(31);
  long covered_bins = 0, arcs = 0;
  EXPECT_EQ(WrongBins(rng, 50000, false, &covered_bins, &arcs), 0);
  // Not so cautious as to be useless: a neighbour's arc covers about 20 bins whole on average
  // (a third of the circle at ratio 1); the tables find most of them.
  EXPECT_GT(static_cast<double>(covered_bins) / static_cast<double>(arcs), 8.0);
}

TEST(FieldArcBinsTest, CheckCatchesAPlantedFault) {
  Rng rng(32);
  long covered_bins = 0, arcs = 0;
  EXPECT_GT(WrongBins(rng, 1000, true, &covered_bins, &arcs), 400);
}

// A candidate far from or near the origin with up to 14 neighbours of random radii within
// reach, some clustered so that they cover the whole circle.
struct Scene {
  Vec2 centre;
  double t;
  std::vector<Vec2> neighbours;
  std::vector<double> radii;
};

Scene RandomScene(Rng& rng) {
  Scene scene;
  scene.t = std::pow(10.0, rng.Uniform(-2, 3));
  scene.centre = {rng.Uniform(-1e3, 1e3) * scene.t, rng.Uniform(-1e3, 1e3) * scene.t};
  const int count = static_cast<int>(rng.Below(15));
  for (int n = 0; n < count; ++n) {
    const double r = scene.t * (rng.Uniform() < 0.5 ? rng.Uniform(0.3, 1.0) : AwkwardRatio(rng));
    const double m = std::max(r, scene.t);
    const Vec2 o = AwkwardOffset(rng, m / scene.t);
    const Vec2 q = {scene.centre.x + o.x * scene.t, scene.centre.y + o.y * scene.t};
    const double reach = scene.t + m;
    const Vec2 offset = {q.x - scene.centre.x, q.y - scene.centre.y};
    if (SquaredLength(offset) < reach * reach && (offset.x != 0.0 || offset.y != 0.0)) {
      scene.neighbours.push_back(q);
      scene.radii.push_back(r);
    }
  }
  return scene;
}

// The boundary the plain way: every arc cut, in order, leaving out neighbour `skip`.
AvailableBoundary CutEveryArc(const Scene& scene, size_t skip = SIZE_MAX) {
  AvailableBoundary boundary;
  boundary.Reset();
  for (size_t n = 0; n < scene.neighbours.size(); ++n) {
    if (n == skip) continue;
    const Vec2 o = {scene.neighbours[n].x - scene.centre.x, scene.neighbours[n].y - scene.centre.y};
    KeyArc arc{0, 0};
    Cut(boundary, DiskArc(o, scene.t, std::max(scene.radii[n], scene.t), &arc), arc);
  }
  return boundary;
}

AvailableBoundary ByBins(const Scene& scene, FieldCandidateBoundary& builder) {
  builder.Start(scene.t);
  for (size_t n = 0; n < scene.neighbours.size(); ++n) {
    const Vec2 o = {scene.neighbours[n].x - scene.centre.x, scene.neighbours[n].y - scene.centre.y};
    if (builder.Add(o, std::max(scene.radii[n], scene.t))) break;
  }
  AvailableBoundary boundary;
  builder.Finish(boundary);
  return boundary;
}

TEST(FieldCandidateBoundaryTest, BinsLeaveTheRangesOfCuttingEveryArc) {
  Rng rng(33);
  FieldCandidateBoundary builder;
  int empty = 0, with_ranges = 0;
  for (int trial = 0; trial < 40000; ++trial) {
    const Scene scene = RandomScene(rng);
    const AvailableBoundary built = ByBins(scene, builder);
    ASSERT_TRUE(SameRanges(built, CutEveryArc(scene))) << "trial " << trial;
    empty += built.empty();
    with_ranges += !built.empty();
  }
  EXPECT_GT(empty, 1000);
  EXPECT_GT(with_ranges, 1000);
}

TEST(FieldCandidateBoundaryTest, ComparisonCatchesAPlantedMissingArc) {
  Rng rng(34);
  FieldCandidateBoundary builder;
  int caught = 0, tried = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Scene scene = RandomScene(rng);
    if (scene.neighbours.empty()) continue;
    ++tried;
    caught +=
        !SameRanges(ByBins(scene, builder), CutEveryArc(scene, rng.Below(scene.neighbours.size())));
  }
  EXPECT_GT(caught, tried / 4);
}

}  // namespace
}  // namespace scallop
