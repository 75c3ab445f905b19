// StreamRemainder against brute force: for random worlds, rectangles and
// break points, the points of the remainder rectangles, in order, are exactly
// the points of the whole rectangle whose region comes after the last one
// received (by row, then column, read from each point's id), in the same
// order. A planted wrong remainder is caught by the same comparison.
#include "stream_resume.h"

#include <gtest/gtest.h>

#include <functional>
#include <tuple>

#include "scallop/plane/plane_engine.h"
#include "scallop/plane/point_id.h"
#include "tests/test_worlds.h"

namespace scallop {
namespace {

// The points of `rect` after region `last` in stream order: the oracle.
PlanePoints PointsAfter(const PlanePoints& whole, RegionKey last) {
  PlanePoints after;
  for (size_t k = 0; k < whole.ids.size(); ++k) {
    const RegionKey region = DecodePointId(whole.ids[k], last).region;
    if (std::tie(region.j, region.i) > std::tie(last.j, last.i)) {
      after.ids.push_back(whole.ids[k]);
      after.positions.push_back(whole.positions[k]);
    }
  }
  return after;
}

PlanePoints PointsOf(PlaneEngine& engine, const World& world, const std::vector<Rect>& rects) {
  PlanePoints joined;
  for (const Rect& rect : rects) {
    StatusOr<PlanePoints> part = engine.Points(world, rect);
    EXPECT_TRUE(part.ok()) << part.status().message();
    if (!part.ok()) continue;
    joined.ids.insert(joined.ids.end(), part->ids.begin(), part->ids.end());
    joined.positions.insert(joined.positions.end(), part->positions.begin(), part->positions.end());
  }
  return joined;
}

using Remainder = std::function<std::vector<Rect>(const Rect&, RegionKey, double)>;

// How many of `trials` random breaks `remainder` resumes wrongly.
int WrongResumes(const Remainder& remainder, int trials, uint64_t seed) {
  PlaneEngine engine({.threads = 1});
  Rng dice(seed);
  int wrong = 0;
  for (int trial = 0; trial < trials; ++trial) {
    const double d = trial % 3 == 0 ? 1.0 : dice.Uniform(0.3, 2.0);
    const World world = ValidWorld({.seed = dice.NextBits(), .min_distance = d});
    const double x = dice.Uniform(-500, 500) * d, y = dice.Uniform(-500, 500) * d;
    const Rect rect{x, y, x + dice.Uniform(1, 80) * d, y + dice.Uniform(1, 80) * d};
    const StatusOr<PlanePoints> whole = engine.Points(world, rect);
    EXPECT_TRUE(whole.ok()) << whole.status().message();
    if (!whole.ok() || whole->ids.empty()) continue;
    // Break after the region of a random point received (so a region with a
    // chunk), now and then after the very last one.
    const size_t k = trial % 5 == 0 ? whole->ids.size() - 1
                                    : static_cast<size_t>(dice.Uniform() * whole->ids.size());
    const RegionLayout layout(d);
    const RegionKey last = layout.RegionOf(whole->positions[k].x, whole->positions[k].y);
    const PlanePoints expected = PointsAfter(*whole, last);
    const PlanePoints got = PointsOf(engine, world, remainder(rect, last, d));
    if (got.ids != expected.ids || got.positions != expected.positions) ++wrong;
  }
  return wrong;
}

TEST(StreamResumeTest, RemainderIsExactlyWhatCameAfter) {
  EXPECT_EQ(WrongResumes(client::StreamRemainder, 120, 4242), 0) << "seed 4242";
}

TEST(StreamResumeTest, LastRegionOfTheRectangleLeavesNothing) {
  const Rect rect{0.5, 0.5, 40, 30};  // regions (0..2, 0..1) at d = 1
  EXPECT_TRUE(client::StreamRemainder(rect, {2, 1}, 1.0).empty());
  EXPECT_EQ(client::StreamRemainder(rect, {2, 0}, 1.0).size(), 1u);  // the next row only
  EXPECT_EQ(client::StreamRemainder(rect, {1, 0}, 1.0).size(), 2u);
}

// Planted faults: resuming at the last region (it comes twice), or skipping
// the rest of its row (points go missing), must be caught.
TEST(StreamResumeTest, PlantedWrongRemaindersAreCaught) {
  const Remainder repeats_last = [](const Rect& rect, RegionKey last, double d) {
    const Rect region = RegionLayout(d).RegionRect(last);
    std::vector<Rect> rects = client::StreamRemainder(rect, last, d);
    rects.insert(rects.begin(), Rect{std::max(rect.x0, region.x0), std::max(rect.y0, region.y0),
                                     std::min(rect.x1, region.x1), std::min(rect.y1, region.y1)});
    return rects;
  };
  const Remainder skips_row = [](const Rect& rect, RegionKey last, double d) {
    std::vector<Rect> rects = client::StreamRemainder(rect, last, d);
    if (rects.size() == 2) rects.erase(rects.begin());
    return rects;
  };
  EXPECT_GT(WrongResumes(repeats_last, 20, 99), 10);
  EXPECT_GT(WrongResumes(skips_row, 20, 99), 0);
}

}  // namespace
}  // namespace scallop
