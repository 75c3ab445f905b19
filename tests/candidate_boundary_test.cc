// A3's candidate boundary by bins (arc_bins.h, candidate_boundary.h) against
// brute force: the bins of an arc and of a neighbour's table cell hold for
// the keys A3 computes, and building a boundary by bins leaves exactly the
// ranges that cutting every arc leaves. The same for a layered world's
// exclusion disks (boundary_exclusions.h): the second intersection rule
// against distances, DiskBins' tables, and the cuts. Each check is shown to
// catch a planted fault.
#include "scallop/sampling/candidate_boundary.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <span>
#include <vector>

#include "scallop/random/rng.h"
#include "scallop/sampling/arc_bins.h"
#include "scallop/sampling/available_boundary.h"
#include "scallop/sampling/boundary_arcs.h"
#include "scallop/sampling/boundary_exclusions.h"
#include "scallop/sampling/spacing.h"
#include "tests/arc_bin_checks.h"

namespace scallop {
namespace {

using arc_bin_checks::ArcHolds;
using arc_bin_checks::AwkwardKey;
using arc_bin_checks::BinErrors;
using arc_bin_checks::SameRanges;

TEST(ArcBinsTest, BinsOfHoldForRandomArcs) {
  Rng rng(11);
  int arcs_covering_some = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const KeyArc arc = {AwkwardKey(rng), AwkwardKey(rng)};
    const ArcBins bins = BinsOf(arc);
    ASSERT_EQ(BinErrors(arc, bins), 0) << arc.from_key << " " << arc.to_key;
    ASSERT_EQ(bins.covered & ~bins.reached, 0u);
    arcs_covering_some += bins.covered != 0;
  }
  EXPECT_GT(arcs_covering_some, 10000);  // the bins are not left empty to be safe
}

TEST(ArcBinsTest, BinErrorsCatchesPlantedFaults) {
  const KeyArc arc = {0.30, 0.90};  // bins 4.8 to 14.4: covers 5 to 13
  const ArcBins bins = BinsOf(arc);
  EXPECT_EQ(BinErrors(arc, bins), 0);
  EXPECT_GT(BinErrors(arc, {bins.covered | (bins.covered << 1), bins.reached}), 0);
  EXPECT_GT(BinErrors(arc, {bins.covered, bins.reached & ~(uint64_t{1} << 4)}), 0);
}

// A neighbour's offset from the candidate, in units of s, with |o| < 2:
// mostly uniform over the annulus A3 sees (1 to 2), and often at the
// table's cell bounds, on the axes, near tangency or near |o| = 1.
Vec2 AwkwardOffset(Rng& rng) {
  const double u = rng.Uniform();
  if (u < 0.15) {  // on cell bounds of the table (sixteenths)
    const Vec2 o = {static_cast<double>(rng.Below(64)) / 16 - 2,
                    static_cast<double>(rng.Below(64)) / 16 - 2};
    if (SquaredLength(o) < 4 && SquaredLength(o) > 0) return o;
  }
  const double angle = u < 0.25 ? rng.Below(8) * std::numbers::pi / 4 : rng.Uniform(0, 7);
  double length = std::sqrt(rng.Uniform(1.0, 4.0));
  if (u > 0.85) length = 2 - std::pow(10.0, -rng.Uniform(1, 15));  // near tangency
  if (u > 0.95) length = 1 + rng.Uniform(-1e-9, 1e-9);
  return {length * std::cos(angle), length * std::sin(angle)};
}

// The arc A3 computes for a neighbour at `offset` (spacing s).
KeyArc ComputedArc(Vec2 offset, double spacing) {
  KeyArc arcs[2];
  CoveredArcs(offset, offset, spacing * spacing, arcs);
  return arcs[0];
}

TEST(ArcBinsTest, NeighbourBinsHoldForTheArcsA3Computes) {
  Rng rng(12);
  long covered_bins = 0;
  // How far from the bins of the computed arc itself the table is, on average.
  long lost_covered = 0, extra_reached = 0, looked_up = 0;
  for (const double spacing : {1.0, 1e-3, 7.3, 3e5}) {
    const NeighbourBins table(spacing);
    for (int trial = 0; trial < 40000; ++trial) {
      const Vec2 unit_offset = AwkwardOffset(rng);
      const Vec2 offset = {unit_offset.x * spacing, unit_offset.y * spacing};
      if (!(SquaredLength(offset) < 4 * spacing * spacing)) continue;  // Of's REQUIRES
      const KeyArc arc = ComputedArc(offset, spacing);
      const ArcBins bins = table.Of(offset);
      const int errors = BinErrors(arc, bins);
      EXPECT_EQ(errors, 0) << "offset " << unit_offset.x << ", " << unit_offset.y << " spacing "
                           << spacing;
      if (errors != 0) return;
      covered_bins += std::popcount(bins.covered);
      const ArcBins exact = BinsOf(arc);
      lost_covered += std::popcount(exact.covered & ~bins.covered);
      extra_reached += std::popcount(bins.reached & ~exact.reached);
      ++looked_up;
    }
  }
  EXPECT_GT(covered_bins, 0);
  // Not so cautious as to be useless: measured 0.99 and 1.38 bins an arc.
  EXPECT_LT(static_cast<double>(lost_covered) / static_cast<double>(looked_up), 1.5);
  EXPECT_LT(static_cast<double>(extra_reached) / static_cast<double>(looked_up), 2.0);
}

TEST(ArcBinsTest, NeighbourCheckCatchesAPlantedFault) {
  // The same check, on a table whose covered bins reach one bin too far:
  // it must fail for many offsets.
  Rng rng(13);
  const NeighbourBins table(1.0);
  int failures = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    const Vec2 offset = AwkwardOffset(rng);
    ArcBins bins = table.Of(offset);
    bins.covered |= std::rotl(bins.covered, 1);
    failures += BinErrors(ComputedArc(offset, 1.0), bins) != 0;
  }
  EXPECT_GT(failures, 100);
}

// How many of `trials` neighbours, at awkward offsets from centres near the origin and far
// from it, `lookup(table, q, centre)` gives other bins than the scalar Of(q - centre) that the
// tables' checks above vouch for.
template <typename Lookup>
int LaneLookupMismatches(uint64_t seed, int trials, Lookup lookup) {
  Rng rng(seed);
  int mismatches = 0;
  for (const double spacing : {1.0, 1e-3, 7.3, 3e5}) {
    const NeighbourBins table(spacing);
    for (int trial = 0; trial < trials; ++trial) {
      // Centres up to 2^32 spacings out, where q - centre rounds.
      const double reach = std::ldexp(spacing, static_cast<int>(rng.Below(33)));
      const Vec2 centre = {rng.Uniform(-reach, reach), rng.Uniform(-reach, reach)};
      const Vec2 unit_offset = AwkwardOffset(rng);
      const Vec2 q = {centre.x + unit_offset.x * spacing, centre.y + unit_offset.y * spacing};
      if (!(SquaredLength(q - centre) < 4 * spacing * spacing)) continue;  // Of's REQUIRES
      const ArcBins expected = table.Of(q - centre), actual = lookup(table, q, centre);
      mismatches += expected.covered != actual.covered || expected.reached != actual.reached;
    }
  }
  return mismatches;
}

TEST(ArcBinsTest, NeighbourBinsInLanesGiveTheScalarLookup) {
  EXPECT_EQ(LaneLookupMismatches(14, 40000,
                                 [](const NeighbourBins& table, Vec2 q, Vec2 centre) {
                                   return table.Of(q, centre);
                                 }),
            0);
}

TEST(ArcBinsTest, LaneLookupCheckCatchesAPlantedFault) {
  // The same comparison against a lookup that swaps the lanes (row for column): it must differ
  // for many offsets.
  const int mismatches =
      LaneLookupMismatches(15, 1000, [](const NeighbourBins& table, Vec2 q, Vec2 centre) {
        return table.Of(Vec2{q.y, q.x}, Vec2{centre.y, centre.x});
      });
  EXPECT_GT(mismatches, 1000);
}

TEST(AvailableBoundaryBinsTest, ResetToBinsGivesARangeToEachRun) {
  Rng rng(14);
  AvailableBoundary boundary;
  for (int trial = 0; trial < 5000; ++trial) {
    // Sparse, dense and all-or-nothing masks.
    uint64_t bins = rng.NextBits();
    if (trial % 3 == 1) bins &= rng.NextBits();
    if (trial % 3 == 2) bins |= rng.NextBits();
    if (trial == 0) bins = 0;
    if (trial == 1) bins = ~uint64_t{0};
    boundary.ResetToBins(bins);
    uint64_t seen = 0;
    double previous_end = -1;
    for (const auto& range : boundary.ranges()) {
      ASSERT_LT(previous_end, range.begin);  // sorted, and no two runs touch
      previous_end = range.end;
      for (int k = 0; k < 64; ++k) {
        const double middle = (k + 0.5) / kBinsPerKey;
        if (range.begin < middle && middle < range.end) seen |= uint64_t{1} << k;
      }
    }
    ASSERT_EQ(seen, bins);
  }
  boundary.ResetToBins(~uint64_t{0});
  ASSERT_EQ(boundary.ranges().size(), 1u);
  EXPECT_EQ(boundary.ranges()[0].begin, 0.0);
  EXPECT_EQ(boundary.ranges()[0].end, kFullTurnKey);
}

// A candidate at `centre` (now and then far from the origin, where offsets
// carry rounding) with neighbours within 2 s, some clustered so that they
// cover its whole circle, and now and then an arc outside the domain.
struct Scene {
  Vec2 centre;
  std::vector<Vec2> neighbours;
  std::vector<KeyArc> other_arcs;
};

Scene RandomScene(Rng& rng, double spacing) {
  Scene scene;
  scene.centre = {rng.Uniform(-1e3, 1e3), rng.Uniform(-1e3, 1e3)};
  if (rng.Uniform() < 0.2)
    scene.centre = {scene.centre.x + 3e6 * spacing, scene.centre.y - 1e6 * spacing};
  const int count = static_cast<int>(rng.Below(14));
  for (int n = 0; n < count; ++n) {
    const Vec2 o = AwkwardOffset(rng);
    const Vec2 q = {scene.centre.x + o.x * spacing, scene.centre.y + o.y * spacing};
    if (SquaredLength(q - scene.centre) < 4 * spacing * spacing) scene.neighbours.push_back(q);
  }
  if (rng.Uniform() < 0.2) scene.other_arcs.push_back({AwkwardKey(rng), AwkwardKey(rng)});
  return scene;
}

// The boundary the plain way: every arc cut, in order.
AvailableBoundary CutEveryArc(const Scene& scene, double spacing, size_t skip = SIZE_MAX) {
  AvailableBoundary boundary;
  boundary.Reset();
  for (const KeyArc& arc : scene.other_arcs) boundary.SubtractArc(arc.from_key, arc.to_key);
  for (size_t n = 0; n < scene.neighbours.size(); ++n) {
    if (n == skip) continue;
    const KeyArc arc = ComputedArc(scene.neighbours[n] - scene.centre, spacing);
    boundary.SubtractArc(arc.from_key, arc.to_key);
  }
  return boundary;
}

TEST(CandidateBoundaryTest, BuildLeavesTheRangesOfCuttingEveryArc) {
  Rng rng(15);
  int empty = 0, with_ranges = 0;
  for (const double spacing : {1.0, 0.37, 1e4}) {
    CandidateBoundary builder(spacing);
    AvailableBoundary built;
    for (int trial = 0; trial < 20000; ++trial) {
      const Scene scene = RandomScene(rng, spacing);
      builder.Build(scene.centre, scene.other_arcs, scene.neighbours, built);
      const AvailableBoundary expected = CutEveryArc(scene, spacing);
      ASSERT_TRUE(SameRanges(built, expected)) << "trial " << trial << " spacing " << spacing;
      empty += built.empty();
      with_ranges += !built.empty();
    }
  }
  // Both outcomes were exercised, many times.
  EXPECT_GT(empty, 1000);
  EXPECT_GT(with_ranges, 1000);
}

TEST(CandidateBoundaryTest, ComparisonCatchesAPlantedMissingArc) {
  // Leaving one neighbour's arc out must show in the comparison, often.
  Rng rng(16);
  CandidateBoundary builder(1.0);
  AvailableBoundary built;
  int caught = 0, tried = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Scene scene = RandomScene(rng, 1.0);
    if (scene.neighbours.empty()) continue;
    ++tried;
    builder.Build(scene.centre, scene.other_arcs, scene.neighbours, built);
    caught += !SameRanges(built, CutEveryArc(scene, 1.0, rng.Below(scene.neighbours.size())));
  }
  EXPECT_GT(caught, tried / 4);
}

// The second intersection rule against distances: on the circle of radius rho about c, a spot
// well inside the disk (radius sigma about c + o) lies on the computed arc, one well outside
// does not; kWhole and kNone agree with every spot.
TEST(DiskArcTest, CoveredArcOfCircleAgreesWithDistances) {
  Rng rng(21);
  int arcs = 0, wholes = 0, nones = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const double rho = std::pow(10.0, rng.Uniform(-2, 2));
    const double sigma = rho * rng.Uniform(0.1, 3.0);
    const double angle = rng.Uniform(0, 7);
    double length = rng.Uniform(0, 1.2 * (rho + sigma));
    if (trial % 5 == 0) length = (rho + sigma) * (1 - std::pow(10.0, -rng.Uniform(1, 12)));
    if (trial % 5 == 1) length = std::abs(rho - sigma) * (1 + std::pow(10.0, -rng.Uniform(1, 12)));
    const Vec2 o = {length * std::cos(angle), length * std::sin(angle)};
    KeyArc arc{0, 0};
    const DiskCover cover = CoveredArcOfCircle(o, rho, sigma, arc);
    arcs += cover == DiskCover::kArc;
    wholes += cover == DiskCover::kWhole;
    nones += cover == DiskCover::kNone;
    for (int k = 0; k < 256; ++k) {
      const double key = AwkwardKey(rng);
      const Vec2 v = DirectionAtKey(key);
      const double scale = rho / Length(v);
      const Vec2 x = {scale * v.x, scale * v.y};
      const double distance = Length(x - o);
      const bool inside = distance<sigma*(1 - 1e-6), outside = distance> sigma * (1 + 1e-6);
      const bool on_arc =
          cover == DiskCover::kWhole || (cover == DiskCover::kArc && ArcHolds(arc, key, key));
      ASSERT_TRUE(!inside || on_arc) << "trial " << trial << " key " << key;
      ASSERT_TRUE(!outside || !on_arc) << "trial " << trial << " key " << key;
    }
  }
  EXPECT_GT(arcs, 5000);
  EXPECT_GT(wholes, 100);
  EXPECT_GT(nones, 1000);
}

// DiskBins' tables hold for the arcs CoveredArcOfCircle computes, for disk radii anywhere within
// the table's slack of its ratio, and any circle radius; and are not uselessly cautious.
TEST(DiskArcTest, DiskBinsHoldForTheArcsComputed) {
  Rng rng(22);
  long looked_up = 0, lost_covered = 0, planted = 0, caught = 0;
  for (const double ratio : {0.5, 0.88, 1.0, 1.5, 2.0}) {
    const DiskBins* table = DiskBins::ForRatio(ratio);
    ASSERT_NE(table, nullptr);
    for (const double rho : {1.0, 1e-3, 7.3}) {
      for (int trial = 0; trial < 20000; ++trial) {
        const double sigma = rho * ratio * (1 + DiskBins::kRatioSlack * rng.Uniform(-1, 1));
        const double angle =
            trial % 7 == 0 ? rng.Below(8) * std::numbers::pi / 4 : rng.Uniform(0, 7);
        double length = rng.Uniform(0, rho + sigma);
        if (trial % 3 == 0) length = (rho + sigma) * (1 - std::pow(10.0, -rng.Uniform(1, 15)));
        if (trial % 3 == 1) length = std::abs(rho - sigma) + rng.Uniform(-1e-9, 1e-9) * rho;
        const Vec2 o = {length * std::cos(angle), length * std::sin(angle)};
        if (!(SquaredLength(o) < (rho + sigma) * (rho + sigma))) continue;  // Of's REQUIRES
        KeyArc arc{0, 0};
        const DiskCover cover = CoveredArcOfCircle(o, rho, sigma, arc);
        const ArcBins bins = table->Of(o, 16 / rho);
        if (cover == DiskCover::kNone) {
          ASSERT_EQ(bins.covered, 0u) << "ratio " << ratio << " trial " << trial;
          continue;
        }
        if (cover == DiskCover::kWhole) {
          ASSERT_EQ(bins.reached, ~uint64_t{0});
          continue;
        }
        ASSERT_EQ(BinErrors(arc, bins), 0) << "ratio " << ratio << " trial " << trial;
        lost_covered += std::popcount(BinsOf(arc).covered & ~bins.covered);
        ++looked_up;
        // A planted fault: covered one bin too far is caught.
        const uint64_t too_far = bins.covered | std::rotl(bins.covered, 1);
        planted += too_far != bins.covered;
        caught += too_far != bins.covered && BinErrors(arc, {too_far, bins.reached}) != 0;
      }
    }
  }
  // Measured 2.7 bins an arc (the margin covers the ratio's slack), against about 1 for
  // NeighbourBins.
  EXPECT_LT(static_cast<double>(lost_covered) / static_cast<double>(looked_up), 4.0);
  EXPECT_GT(planted, looked_up / 4);
  EXPECT_GT(caught, planted / 5);  // measured 36%: the table loses bins that one more may be
  EXPECT_EQ(DiskBins::ForRatio(DiskBins::kMaxRatio * 1.01), nullptr);
}

// Fewer than `bound` disks (radii 0.88, 0.6 and 2.5, the last without a table) near the circle
// of radius about 1 about `centre`, some holding it whole.
std::vector<ExclusionDisk> RandomDisks(Rng& rng, Vec2 centre, uint64_t bound) {
  std::vector<ExclusionDisk> disks;
  const double radii[] = {0.88, 0.6, 2.5};
  const int count = static_cast<int>(rng.Below(bound));
  for (int n = 0; n < count; ++n) {
    const double r = radii[rng.Below(3)];
    const double angle = rng.Uniform(0, 7), length = rng.Uniform(0.2, 1.2) * (1 + r);
    disks.push_back(
        {{centre.x + length * std::cos(angle), centre.y + length * std::sin(angle)}, r});
  }
  return disks;
}

// A circle's centre for trial `trial`, a quarter of them far from the origin, with the largest
// coordinate of a run about it and the spacing of d = 1 there.
struct Place {
  Vec2 centre;
  double max_abs;
  double spacing;
};
Place RandomPlace(Rng& rng, int trial) {
  const double far = trial % 4 == 0 ? 3e6 : 0.0;
  const Vec2 centre = {far + rng.Uniform(-50, 50), rng.Uniform(-50, 50)};
  const double max_abs = std::abs(centre.x) + 60;
  return {centre, max_abs, SpacingFor(1.0, max_abs)};
}

// Cuts from `boundary` (of the circle of radius `spacing` about `centre`) the arc of every disk
// but `skip`, computed by the second intersection rule, one by one.
void CutEveryDisk(const BoundaryExclusions& exclusions, Vec2 centre, double spacing,
                  AvailableBoundary& boundary, size_t skip = SIZE_MAX) {
  for (size_t k = 0; k < exclusions.size(); ++k) {
    KeyArc arc{0, 0};
    const DiskCover cover = k == skip ? DiskCover::kNone
                                      : CoveredArcOfCircle(exclusions.centre(k) - centre, spacing,
                                                           exclusions.cut_radius(k), arc);
    if (cover == DiskCover::kWhole) boundary.Clear();
    if (cover == DiskCover::kArc) boundary.SubtractArc(arc.from_key, arc.to_key);
  }
}

// BoundaryExclusions cuts from a point's circle exactly what cutting every disk's arc would, by
// tables or not (radii with and without one), far from the origin too, fresh or Reset after
// other disks (as a plane engine's scratch keeps it); leaving a disk out is caught.
TEST(DiskArcTest, CutAroundPointLeavesTheRangesOfCuttingEveryArc) {
  Rng rng(23);
  int empty = 0, with_ranges = 0, caught = 0, tried = 0;
  BoundaryExclusions kept;  // Reset with each trial's disks
  for (int trial = 0; trial < 4000; ++trial) {
    const double d = 1.0;
    const Place place = RandomPlace(rng, trial);
    const Vec2 centre = place.centre;
    const double max_abs = place.max_abs, spacing = place.spacing;
    // Up to 8 disks within about 3.5 of the centre: rows of the disk grid hold more than the
    // search's two unrolled ones too.
    const std::vector<ExclusionDisk> disks = RandomDisks(rng, centre, 9);
    BoundaryExclusions exclusions(disks, d, spacing, max_abs);
    kept.Reset(disks, d, spacing, max_abs);
    AvailableBoundary start;
    start.Reset();
    if (rng.Uniform() < 0.5) start.SubtractArc(AwkwardKey(rng), AwkwardKey(rng));
    AvailableBoundary built = start;
    exclusions.CutAroundPoint(centre, built);
    const auto cut_every = [&](size_t skip) {
      AvailableBoundary expected = start;
      CutEveryDisk(exclusions, centre, spacing, expected, skip);
      return expected;
    };
    ASSERT_TRUE(SameRanges(built, cut_every(SIZE_MAX))) << "trial " << trial;
    AvailableBoundary built_by_kept = start;
    kept.CutAroundPoint(centre, built_by_kept);
    ASSERT_TRUE(SameRanges(built_by_kept, built)) << "trial " << trial;
    empty += built.empty();
    with_ranges += !built.empty();
    if (exclusions.size() > 0) {
      ++tried;
      caught += !SameRanges(built, cut_every(rng.Below(exclusions.size())));
    }
  }
  EXPECT_GT(empty, 200);
  EXPECT_GT(with_ranges, 1000);
  EXPECT_GT(caught, tried / 4);
}

// Disks on a jittered square lattice of `count` x `count` about `low`, `step` apart and moved by
// up to `jitter` each way (so at least step - 2 jitter apart), with radii drawn from `radii`: a
// later layer's disks, sparse, as the earlier layers' points are.
std::vector<ExclusionDisk> LatticeDisks(Rng& rng, Vec2 low, int count, double step, double jitter,
                                        std::span<const double> radii) {
  std::vector<ExclusionDisk> disks;
  for (int j = 0; j < count; ++j) {
    for (int i = 0; i < count; ++i) {
      const Vec2 at = {low.x + i * step + rng.Uniform(-jitter, jitter),
                       low.y + j * step + rng.Uniform(-jitter, jitter)};
      disks.push_back({at, radii[rng.Below(radii.size())]});
    }
  }
  return disks;
}

// The disk search on sparse disks, as a forest's later layers have them: no two in a cell of the
// search (found by its cells' bits), on a few cells and on many (numbered from the bits alone), and
// with the windows too wide for the bits and the cells holding two (the rows scanned). Each point's
// circle and each disk's circle is cut as cutting every disk's arc would (the oracle, over all
// disks), and each disk the search keeps decides Excludes on the circle as a test of every disk
// does; leaving one disk out of the oracle is caught.
TEST(DiskArcTest, SearchOfSparseDisksFindsEveryDiskNearTheCircle) {
  Rng rng(26);
  struct Case {
    const char* name;
    int count;  // lattice points a side
    double step, jitter;
    std::vector<double> radii;
    int pairs;  // disks added 0.01 from another: cells holding two
  };
  // Radii 0.88 and 0.6 file in cells 0.88 wide (diagonal 1.25 < 1.76 - 2 x 0.2); radius 0.3 in
  // cells 0.3 wide (diagonal 0.42 < 0.9), where a search about a circle of radius 1 spans 9 or
  // more.
  const Case cases[] = {{"few cells", 20, 1.76, 0.2, {0.88, 0.6}, 0},
                        {"many cells", 150, 1.76, 0.2, {0.88, 0.6}, 0},
                        {"wide windows", 30, 1.5, 0.3, {0.3}, 0},
                        {"cells holding two", 20, 1.76, 0.2, {0.88, 0.6}, 10}};
  for (const Case& test : cases) {
    const double d = 1.0;
    const Vec2 low = {rng.Uniform(-50, 50), rng.Uniform(-50, 50)};
    std::vector<ExclusionDisk> disks =
        LatticeDisks(rng, low, test.count, test.step, test.jitter, test.radii);
    for (int n = 0; n < test.pairs; ++n) {
      const ExclusionDisk& twin = disks[rng.Below(disks.size())];
      disks.push_back({{twin.centre.x + 0.01, twin.centre.y + 0.01}, twin.radius});
    }
    const double side = test.count * test.step, max_abs = std::abs(low.x) + std::abs(low.y) + side;
    const double spacing = SpacingFor(d, max_abs);
    BoundaryExclusions exclusions(disks, d, spacing, max_abs);
    int caught = 0, tried = 0, excluded = 0, free = 0;
    for (int trial = 0; trial < 300; ++trial) {
      const Vec2 centre = {low.x + rng.Uniform(-1, side), low.y + rng.Uniform(-1, side)};
      AvailableBoundary built;
      built.Reset();
      exclusions.CutAroundPoint(centre, built);
      AvailableBoundary expected;
      expected.Reset();
      CutEveryDisk(exclusions, centre, spacing, expected);
      ASSERT_TRUE(SameRanges(built, expected)) << test.name << " trial " << trial;
      // Excludes, after the search, against a test of every disk, on the circle.
      if (exclusions.GatherAroundPoint(centre)) {
        for (int n = 0; n < 8; ++n) {
          const double angle = rng.Uniform(0, 7);
          const Vec2 x = {centre.x + spacing * std::cos(angle),
                          centre.y + spacing * std::sin(angle)};
          ASSERT_EQ(exclusions.Excludes(x), exclusions.AnyExcludes(x))
              << test.name << " trial " << trial << " x " << x.x << "," << x.y;
          excluded += exclusions.Excludes(x);
          free += !exclusions.Excludes(x);
        }
      }
      // The planted fault: the nearest disk left out of the oracle.
      size_t nearest = 0;
      for (size_t k = 1; k < exclusions.size(); ++k) {
        if (SquaredDistance(exclusions.centre(k), centre) <
            SquaredDistance(exclusions.centre(nearest), centre)) {
          nearest = k;
        }
      }
      AvailableBoundary planted;
      planted.Reset();
      CutEveryDisk(exclusions, centre, spacing, planted, nearest);
      ++tried;
      caught += !SameRanges(built, planted);

      // A disk's circle, the other disks cut from it (no points).
      const size_t k = rng.Below(exclusions.size());
      const double radius = exclusions.cut_radius(k);
      AvailableBoundary around;
      around.Reset();
      exclusions.CutAroundDisk(k, {}, around);
      AvailableBoundary around_expected;
      around_expected.Reset();
      CutEveryDisk(exclusions, exclusions.centre(k), radius, around_expected, k);
      ASSERT_TRUE(SameRanges(around, around_expected)) << test.name << " disk " << k;
    }
    EXPECT_GT(excluded, 100) << test.name;
    EXPECT_GT(free, 100) << test.name;
    // Measured 38% to 93%: where other disks' arcs cover the nearest one's, leaving it out
    // changes nothing.
    EXPECT_GT(caught, tried / 4) << test.name;
    std::printf("%s: %d of %d faults caught\n", test.name, caught, tried);
  }
}

// The sampler's two steps for a point's circle in a layered run: the disks near it gathered,
// their whole bins (turned by `turn` bins: 0 but for a planted fault) dropped in Build with the
// points', then their arcs cut.
AvailableBoundary CutInTwoSteps(BoundaryExclusions& exclusions, CandidateBoundary& builder,
                                const Scene& scene, int turn) {
  AvailableBoundary boundary;
  if (!exclusions.GatherAroundPoint(scene.centre)) {
    boundary.Clear();
    return boundary;
  }
  builder.Build(scene.centre, scene.other_arcs, scene.neighbours, boundary,
                std::rotl(exclusions.GatheredCoveredBins(), turn));
  if (!boundary.empty()) exclusions.CutGathered(boundary);
  return boundary;
}

// A point's circle in a layered run: the disks' whole bins dropped with the points' in Build
// (covered_later), then the disks' arcs cut, leaves what cutting every arc (points', disks',
// the domain's) leaves. Dropping one bin too many (a disk's bins turned by one) is caught.
TEST(DiskArcTest, DisksBinsDroppedInBuildLeaveTheRangesOfCuttingEveryArc) {
  Rng rng(24);
  int empty = 0, with_ranges = 0, caught = 0, tried = 0;
  for (int trial = 0; trial < 6000; ++trial) {
    // Scenes lie within 1e3 + 3e6 spacings of the origin.
    const double d = 1.0, max_abs = 4e6;
    const double spacing = SpacingFor(d, max_abs);
    const Scene scene = RandomScene(rng, spacing);
    BoundaryExclusions exclusions(RandomDisks(rng, scene.centre, 6), d, spacing, max_abs);
    CandidateBoundary builder(spacing);
    const AvailableBoundary built = CutInTwoSteps(exclusions, builder, scene, 0);
    AvailableBoundary expected = CutEveryArc(scene, spacing);
    CutEveryDisk(exclusions, scene.centre, spacing, expected);
    ASSERT_TRUE(SameRanges(built, expected)) << "trial " << trial;
    empty += built.empty();
    with_ranges += !built.empty();
    // The planted fault: a disk's whole bins one bin off.
    const uint64_t covered = exclusions.GatheredCoveredBins();
    if (covered != 0 && covered != ~uint64_t{0} && exclusions.GatherAroundPoint(scene.centre)) {
      ++tried;
      caught += !SameRanges(CutInTwoSteps(exclusions, builder, scene, 1), expected);
    }
  }
  EXPECT_GT(empty, 500);
  EXPECT_GT(with_ranges, 1500);
  EXPECT_GT(tried, 500);
  EXPECT_GT(caught, tried / 10);
}

// The circle of an exclusion disk (a pocket's edge) less the other disks' arcs and the points'
// disks' (radius `spacing`) leaves what cutting every arc leaves, whether the points' bins settle
// it before the disks are searched or not; leaving a point or a disk out is caught.
TEST(DiskArcTest, CutAroundDiskLeavesTheRangesOfCuttingEveryArc) {
  Rng rng(25);
  int empty = 0, with_ranges = 0, caught = 0, tried = 0, settled_by_points = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const double d = 1.0;
    const Place place = RandomPlace(rng, trial);
    const Vec2 centre = place.centre;
    const double max_abs = place.max_abs, spacing = place.spacing;
    std::vector<ExclusionDisk> disks = RandomDisks(rng, centre, 6);
    disks.push_back({centre, rng.Uniform() < 0.5 ? 0.88 : 2.5});
    BoundaryExclusions exclusions(disks, d, spacing, max_abs);
    size_t k = 0;  // the disk at `centre`, wherever filing put it
    while (exclusions.centre(k) != centre) ++k;
    const double radius = exclusions.cut_radius(k);
    std::vector<Vec2> points;
    const int count = static_cast<int>(rng.Below(10));
    for (int n = 0; n < count; ++n) {
      const double angle = rng.Uniform(0, 7), length = rng.Uniform(radius, radius + 1.1 * spacing);
      points.push_back({centre.x + length * std::cos(angle), centre.y + length * std::sin(angle)});
    }
    AvailableBoundary start;
    start.Reset();
    if (rng.Uniform() < 0.5) start.SubtractArc(AwkwardKey(rng), AwkwardKey(rng));
    AvailableBoundary built = start;
    exclusions.CutAroundDisk(k, points, built);
    const auto cut_every = [&](size_t skip_disk, size_t skip_point, const AvailableBoundary& from) {
      AvailableBoundary expected = from;
      for (size_t j = 0; j < exclusions.size(); ++j) {
        KeyArc arc{0, 0};
        const DiskCover cover = j == k || j == skip_disk
                                    ? DiskCover::kNone
                                    : CoveredArcOfCircle(exclusions.centre(j) - centre, radius,
                                                         exclusions.cut_radius(j), arc);
        if (cover == DiskCover::kWhole) expected.Clear();
        if (cover == DiskCover::kArc) expected.SubtractArc(arc.from_key, arc.to_key);
      }
      for (size_t n = 0; n < points.size(); ++n) {
        KeyArc arc{0, 0};
        const DiskCover cover = n == skip_point
                                    ? DiskCover::kNone
                                    : CoveredArcOfCircle(points[n] - centre, radius, spacing, arc);
        if (cover == DiskCover::kWhole) expected.Clear();
        if (cover == DiskCover::kArc) expected.SubtractArc(arc.from_key, arc.to_key);
      }
      return expected;
    };
    ASSERT_TRUE(SameRanges(built, cut_every(SIZE_MAX, SIZE_MAX, start))) << "trial " << trial;
    // The first step's verdict alone settles the circle for any start (a pocket's clip): when
    // the points' bins cover it, cutting every arc from the whole circle leaves nothing.
    if (!exclusions.GatherAroundDisk(k, points)) {
      AvailableBoundary whole;
      whole.Reset();
      ASSERT_TRUE(cut_every(SIZE_MAX, SIZE_MAX, whole).empty()) << "trial " << trial;
      ++settled_by_points;
    }
    empty += built.empty();
    with_ranges += !built.empty();
    if (!points.empty()) {
      ++tried;
      caught += !SameRanges(built, cut_every(SIZE_MAX, rng.Below(points.size()), start));
    }
    if (exclusions.size() > 1) {
      ++tried;
      size_t skip = rng.Below(exclusions.size() - 1);
      skip += skip >= k;
      caught += !SameRanges(built, cut_every(skip, SIZE_MAX, start));
    }
  }
  EXPECT_GT(settled_by_points, 20);
  EXPECT_GT(empty, 400);
  EXPECT_GT(with_ranges, 1500);
  EXPECT_GT(caught, tried / 5);
}

}  // namespace
}  // namespace scallop
