// The rectangle rule (plane/query_rect.h) against brute force: the regions a
// half-open rectangle overlaps, found by asking each nearby region whether
// its own rectangle meets the query's; the region bound a square can never
// reach; and the rule's messages naming the field and the limit.
#include "scallop/plane/query_rect.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "scallop/random/rng.h"
#include "tests/test_worlds.h"

namespace scallop {
namespace {

// Region (i, j) overlaps the half-open rect when their half-open rectangles
// share a point: the same definition as Rect::Contains, on both axes.
bool Overlaps(const Rect& a, const Rect& b) {
  return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

// Every region near `rect` tested one by one.
RegionRange BruteForceRange(const RegionLayout& layout, const Rect& rect) {
  const RegionKey centre = layout.RegionOf(rect.x0, rect.y0);
  RegionRange range{{INT64_MAX, INT64_MAX}, {INT64_MIN, INT64_MIN}};
  const auto span = static_cast<int64_t>(std::ceil(rect.Width() / layout.side())) + 2;
  const auto rows = static_cast<int64_t>(std::ceil(rect.Height() / layout.side())) + 2;
  for (int64_t j = centre.j - 1; j <= centre.j + rows; ++j) {
    for (int64_t i = centre.i - 1; i <= centre.i + span; ++i) {
      if (!Overlaps(layout.RegionRect({i, j}), rect)) continue;
      range.low = {std::min(range.low.i, i), std::min(range.low.j, j)};
      range.high = {std::max(range.high.i, i), std::max(range.high.j, j)};
    }
  }
  return range;
}

// Corners on seams exactly, a hair either side of them, and anywhere, for
// d whose region edges are rounded doubles.
double RandomCoordinate(Rng& rng, const RegionLayout& layout) {
  const double seam = layout.RegionRect({static_cast<int64_t>(rng.Below(41)) - 20, 0}).x0;
  switch (rng.Below(4)) {
    case 0:
      return seam;
    case 1:
      return std::nextafter(seam, -INFINITY);
    case 2:
      return std::nextafter(seam, INFINITY);
    default:
      return rng.Uniform(-20.0, 20.0) * layout.side();
  }
}

TEST(QueryRectTest, RegionsOverlappingMatchesBruteForce) {
  const uint64_t seed = 0x9e37;
  Rng rng(seed);
  int mismatches = 0, cases = 0;
  for (double d : {1.0, 0.37, 3.1}) {
    const RegionLayout layout(d);
    for (int n = 0; n < 4000; ++n) {
      double x0 = RandomCoordinate(rng, layout), x1 = RandomCoordinate(rng, layout);
      double y0 = RandomCoordinate(rng, layout), y1 = RandomCoordinate(rng, layout);
      if (x0 == x1 || y0 == y1) continue;
      const Rect rect{std::min(x0, x1), std::min(y0, y1), std::max(x0, x1), std::max(y0, y1)};
      const RegionRange fast = RegionsOverlapping(layout, rect);
      const RegionRange slow = BruteForceRange(layout, rect);
      ++cases;
      if (fast.low != slow.low || fast.high != slow.high) {
        if (++mismatches <= 5) {
          ADD_FAILURE() << "seed " << seed << " d " << d << " rect " << rect.x0 << "," << rect.y0
                        << "," << rect.x1 << "," << rect.y1;
        }
      }
    }
  }
  EXPECT_GT(cases, 10000);
  EXPECT_EQ(mismatches, 0);
}

// The comparison above must notice a range that forgets the rectangle is
// half-open: ending at the region owning x1 itself adds a column whenever x1
// sits on a seam.
TEST(QueryRectTest, BruteForceCatchesAClosedRange) {
  const RegionLayout layout(1.0);
  const Rect on_seams{0, 0, 2 * layout.side(), layout.side()};
  const RegionRange closed{layout.RegionOf(on_seams.x0, on_seams.y0),
                           layout.RegionOf(on_seams.x1, on_seams.y1)};
  const RegionRange slow = BruteForceRange(layout, on_seams);
  EXPECT_NE(closed.high, slow.high);
  EXPECT_EQ(RegionsOverlapping(layout, on_seams).high, slow.high);
  EXPECT_EQ(RegionsOverlapping(layout, on_seams).Count(), 2.0);
}

// A square of any allowed area passes the region bound wherever it lies:
// only thin rectangles can meet it.
TEST(QueryRectTest, NoSquareMeetsTheRegionBound) {
  Rng rng(77);
  const World world = ValidWorld({.seed = 1});
  const RegionLayout layout(world.min_distance());
  for (int n = 0; n < 20000; ++n) {
    const double area = std::exp2(rng.Uniform(-10.0, 36.0));
    const double side = std::sqrt(area);
    const double x0 = rng.Uniform(-1e6, 1e6), y0 = rng.Uniform(-1e6, 1e6);
    const Rect square{x0, y0, x0 + side, y0 + side};
    // The rounded square may exceed `area` by an ulp; allow it.
    const QueryLimit limit{.max_area = square.Width() * square.Height()};
    const Status status = CheckQueryRect(world, square, limit);
    ASSERT_TRUE(status.ok()) << "area " << area << ": " << status.message();
    ASSERT_LE(RegionsOverlapping(layout, square).Count(), MaxRegionsCrossed(limit.max_area));
  }
}

TEST(QueryRectTest, MessagesNameTheFieldAndTheLimit) {
  const World world = ValidWorld({.seed = 1, .min_distance = 0.5});
  const QueryLimit limit{.max_area = 1e4, .name = "max_test_area"};
  const auto message = [&](const Rect& rect, const char* field) {
    const Status status = CheckQueryRect(world, rect, limit, field);
    EXPECT_FALSE(status.ok());
    return status.message();
  };
  EXPECT_EQ(message({0, 0, NAN, 1}, "viewport"), "viewport.x1: must be finite");
  EXPECT_EQ(message({1, 0, 0, 1}, "rect"), "rect: x0 must be less than x1");
  EXPECT_NE(message({0, 0, 1, 0x1p40}, "rect").find("rect.y1: |value| must be at most"),
            std::string::npos);
  // 60 d x 60 d at d = 0.5 is 14400 d^2; the number is printed exactly.
  EXPECT_EQ(message({0, 0, 60, 60}, "rect"),
            "rect: area is 14400 min_distance^2, must be at most 10000 (max_test_area)");
  // A thin sliver of tiny area crosses too many regions.
  EXPECT_NE(message({0, 0, 1e6, 1e-6}, "rect")
                .find("regions of 16 min_distance, at most 172.25 "
                      "(max_test_area / 64 + 16)"),
            std::string::npos);
  EXPECT_EQ(CheckQueryRect(world, {0, 0, 1e6, 1e-6}, limit).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(CheckQueryRect(world, {0, 0, 1, 0x1p40}, limit).code(), StatusCode::kOutOfRange);
  EXPECT_TRUE(CheckQueryRect(world, {0, 0, 50, 50}, limit).ok());
}

// A radius-field world's regions are 6 r_max, not 16 min_distance (d is r_min there), and
// the message counts and names those.
TEST(QueryRectTest, FieldWorldMessagesNameItsRegions) {
  WorldSpec spec{.seed = 1, .algorithm = WorldAlgorithm::kA3};
  spec.radius_field = RadiusFieldSpec{
      .kind = RadiusFieldKind::kNoise, .r_min = 0.5, .r_max = 2.0, .frequency = 0.01};
  const World world = ValidWorld(spec);
  EXPECT_EQ(RegionSideText(world), "6 r_max (r_max = 2)");
  EXPECT_EQ(RegionSideText(ValidWorld({.seed = 1, .min_distance = 0.5})), "16 min_distance");
  // 1e4 r_min^2 allows 172.25 regions; a sliver 12,001 long crosses 1,001 regions of 12.
  const Status status =
      CheckQueryRect(world, {0, 0, 12001, 1e-6}, {.max_area = 1e4, .name = "max_test_area"});
  EXPECT_EQ(status.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(status.message().find("crosses 1001 regions of 6 r_max (r_max = 2), at most 172.25"),
            std::string::npos)
      << status.message();
}

}  // namespace
}  // namespace scallop
