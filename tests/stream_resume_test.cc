// StreamRemainder against brute force: for random worlds, rectangles and
// break points, the points of the remainder rectangles, in order, are exactly
// the points of the whole rectangle whose region comes after the last one
// received (by row, then column, read from each point's id), in the same
// order. StreamResumeRequests the same for layered worlds, with and without
// a layer filter: the requests' points are those after the last chunk's
// (layer, region), the layer read from the points and the region from each
// point's position in its layer's regions. Planted wrong resumes are caught
// by the same comparisons.
#include "stream_resume.h"

#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <tuple>

#include "scallop/plane/layer_regions.h"
#include "scallop/plane/plane_engine.h"
#include "scallop/plane/point_id.h"
#include "scallop/plane/world_layers.h"
#include "tests/field_test_fields.h"
#include "tests/test_worlds.h"
#include "world_messages.h"

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

// A layered world's DescribeWorld answer as far as resuming reads it: each layer's name and
// region side, in the layers' order.
v1::DescribeWorldResponse Description(const World& world) {
  v1::DescribeWorldResponse description;
  description.set_region_side(RegionLayout(world).side());
  for (int k = 0; k < world.layers()->count(); ++k) {
    v1::LayerDescription& layer = *description.add_layers();
    layer.set_name(world.layers()->name(k));
    layer.set_region_side(RegionLayout(world.layers()->world(k)).side());
  }
  return description;
}

LayerMask MaskOf(const World& world, const google::protobuf::RepeatedPtrField<std::string>& names) {
  if (names.empty()) return kAllLayers;
  LayerMask mask = 0;
  for (const std::string& name : names) mask |= LayerMask{1} << world.layers()->LayerNamed(name);
  return mask;
}

// The points the stream of `request` sends, in order: the engine's answer for its rectangle
// and filter (which the server's streams equal, tests/e2e).
PlanePoints Streamed(PlaneEngine& engine, const World& world,
                     const v1::StreamPointsRequest& request) {
  StatusOr<PlanePoints> points =
      engine.Points(world, RectFromMessage(request.rect()), MaskOf(world, request.layers()));
  EXPECT_TRUE(points.ok()) << points.status().message();
  return points.ok() ? *points : PlanePoints{};
}

void Append(const PlanePoints& part, PlanePoints& joined) {
  joined.ids.insert(joined.ids.end(), part.ids.begin(), part.ids.end());
  joined.positions.insert(joined.positions.end(), part.positions.begin(), part.positions.end());
  joined.layers.insert(joined.layers.end(), part.layers.begin(), part.layers.end());
}

using Resume = std::function<std::vector<v1::StreamPointsRequest>(
    const v1::StreamPointsRequest&, const v1::DescribeWorldResponse&, client::StreamPosition)>;

std::vector<v1::StreamPointsRequest> CorrectResume(const v1::StreamPointsRequest& request,
                                                   const v1::DescribeWorldResponse& world,
                                                   client::StreamPosition last) {
  StatusOr<std::vector<v1::StreamPointsRequest>> requests =
      client::StreamResumeRequests(request, world, last);
  EXPECT_TRUE(requests.ok()) << requests.status().message();
  return requests.ok() ? *requests : std::vector<v1::StreamPointsRequest>{};
}

// How many of `trials` random breaks of streams of random filters of `world` `resume` gets
// wrong (points, ids or layers other than the stream's after the break, or in another order).
int WrongLayeredResumes(const World& world, const Resume& resume, int trials, uint64_t seed) {
  PlaneEngine engine({.threads = 1});
  Rng dice(seed);
  const WorldLayers& layers = *world.layers();
  const v1::DescribeWorldResponse description = Description(world);
  int wrong = 0;
  for (int trial = 0; trial < trials; ++trial) {
    v1::StreamPointsRequest request;
    const double side = dice.Uniform(10, 70);
    const double x = dice.Uniform(-200, 200), y = dice.Uniform(-200, 200);
    *request.mutable_rect() = RectToMessage({x, y, x + side, y + dice.Uniform(10, 70)});
    if (trial % 3 != 0) {  // a filter of a random non-empty set, named in a random order
      const LayerMask mask = 1 + static_cast<LayerMask>(dice.Below((1u << layers.count()) - 1));
      for (int k = layers.count() - 1; k >= 0; --k) {
        if (mask >> k & 1) request.add_layers(layers.name(k));
      }
    }
    const PlanePoints whole = Streamed(engine, world, request);
    if (whole.ids.empty()) continue;
    const size_t k = trial % 5 == 0 ? whole.ids.size() - 1
                                    : static_cast<size_t>(dice.Uniform() * whole.ids.size());
    // The oracle: the points whose (layer, region row, region column) come after the break's.
    auto place = [&](size_t n) {
      const RegionKey region = RegionLayout(layers.world(whole.layers[n]))
                                   .RegionOf(whole.positions[n].x, whole.positions[n].y);
      return std::tuple(whole.layers[n], region.j, region.i);
    };
    PlanePoints expected;
    for (size_t n = 0; n < whole.ids.size(); ++n) {
      if (place(n) > place(k)) {
        expected.ids.push_back(whole.ids[n]);
        expected.positions.push_back(whole.positions[n]);
        expected.layers.push_back(whole.layers[n]);
      }
    }
    const auto [layer, j, i] = place(k);
    PlanePoints got;
    for (const v1::StreamPointsRequest& rest :
         resume(request, description, {.layer = layer, .region = {i, j}})) {
      Append(Streamed(engine, world, rest), got);
    }
    if (got.ids != expected.ids || got.positions != expected.positions ||
        got.layers != expected.layers) {
      ++wrong;
    }
  }
  return wrong;
}

// Trees, bushes and rocks (the default matrix); and a world whose middle layer is a noise field
// (regions of 6 r_max, where the others' are 16 d), so that each layer's own regions matter.
World ConstantForest() {
  WorldSpec spec{.seed = 17};
  spec.layers = {{.name = "trees", .min_distance = 8},
                 {.name = "bushes", .min_distance = 3},
                 {.name = "rocks", .min_distance = 1.5}};
  return ValidWorld(spec);
}

World FieldForest() {
  WorldSpec spec{.seed = 23};
  spec.layers = {{.name = "oaks", .min_distance = 5},
                 {.name = "ferns", .radius_field = field_test::NoiseField(3, 1.5, 2.0).spec()},
                 {.name = "moss", .min_distance = 1}};
  return ValidWorld(spec);
}

TEST(StreamResumeTest, LayeredRemainderIsExactlyWhatCameAfter) {
  EXPECT_EQ(WrongLayeredResumes(ConstantForest(), CorrectResume, 40, 515), 0) << "seed 515";
  EXPECT_EQ(WrongLayeredResumes(FieldForest(), CorrectResume, 30, 616), 0) << "seed 616";
}

TEST(StreamResumeTest, ResumeRequestsOfEdgeCases) {
  v1::StreamPointsRequest request;
  *request.mutable_rect() = RectToMessage({0.5, 0.5, 40, 30});
  request.set_world_name("coast");
  v1::DescribeWorldResponse plain;
  plain.set_region_side(16);
  // Broken before the first chunk: the request again; after the last region: nothing.
  StatusOr<std::vector<v1::StreamPointsRequest>> again =
      client::StreamResumeRequests(request, plain, std::nullopt);
  ASSERT_TRUE(again.ok());
  ASSERT_EQ(again->size(), 1u);
  EXPECT_EQ((*again)[0].SerializeAsString(), request.SerializeAsString());
  EXPECT_TRUE(
      client::StreamResumeRequests(request, plain, client::StreamPosition{0, {2, 1}})->empty());
  const StatusOr<std::vector<v1::StreamPointsRequest>> plain_rest =
      client::StreamResumeRequests(request, plain, client::StreamPosition{0, {1, 0}});
  ASSERT_TRUE(plain_rest.ok());
  ASSERT_EQ(plain_rest->size(), 2u);
  EXPECT_EQ((*plain_rest)[0].world_name(), "coast");
  EXPECT_EQ(RectFromMessage((*plain_rest)[0].rect()), (Rect{32, 0.5, 40, 16}));

  const v1::DescribeWorldResponse forest = Description(ConstantForest());
  request.add_layers("rocks");
  request.add_layers("trees");
  // The last region of trees: rocks follow, alone; of rocks: nothing.
  StatusOr<std::vector<v1::StreamPointsRequest>> after_trees =
      client::StreamResumeRequests(request, forest, client::StreamPosition{0, {0, 0}});
  ASSERT_TRUE(after_trees.ok());
  ASSERT_EQ(after_trees->size(), 1u);
  EXPECT_EQ((*after_trees)[0].layers_size(), 1);
  EXPECT_EQ((*after_trees)[0].layers(0), "rocks");
  EXPECT_EQ(RectFromMessage((*after_trees)[0].rect()), RectFromMessage(request.rect()));
  EXPECT_TRUE(
      client::StreamResumeRequests(request, forest, client::StreamPosition{2, {1, 1}})->empty());

  // Errors name the field.
  auto error = [&](const v1::StreamPointsRequest& r, const v1::DescribeWorldResponse& w,
                   client::StreamPosition last) {
    StatusOr<std::vector<v1::StreamPointsRequest>> got = client::StreamResumeRequests(r, w, last);
    return got.ok() ? std::string("ok") : got.status().message();
  };
  EXPECT_EQ(error(request, forest, {1, {0, 0}}).rfind("last.layer: 1 is not", 0), 0u);
  EXPECT_EQ(error(request, forest, {7, {0, 0}}).rfind("last.layer: 7 is not", 0), 0u);
  EXPECT_EQ(error(request, plain, {0, {0, 0}}).rfind("layers: the world has no layers", 0), 0u);
  request.add_layers("ferns");
  EXPECT_EQ(error(request, forest, {0, {0, 0}}), "layers: no layer named 'ferns'");
  request.clear_layers();
  EXPECT_EQ(error(request, plain, {2, {0, 0}}).rfind("last.layer: must be 0", 0), 0u);
  EXPECT_EQ(error(request, v1::DescribeWorldResponse(), {0, {0, 0}}).rfind("region_side:", 0), 0u);
}

// Planted faults: repeating the last region, resuming later layers without the filter, and
// cutting the last layer by the world's regions instead of its own, must be caught.
TEST(StreamResumeTest, PlantedWrongLayeredResumesAreCaught) {
  const Resume repeats_last = [](const v1::StreamPointsRequest& request,
                                 const v1::DescribeWorldResponse& world,
                                 client::StreamPosition last) {
    std::vector<v1::StreamPointsRequest> requests = CorrectResume(request, world, last);
    v1::StreamPointsRequest again = request;
    const double side = world.layers(static_cast<int>(last.layer)).region_side();
    const Rect rect = RectFromMessage(request.rect());
    const Rect region{last.region.i * side, last.region.j * side, (last.region.i + 1) * side,
                      (last.region.j + 1) * side};
    *again.mutable_rect() =
        RectToMessage({std::max(rect.x0, region.x0), std::max(rect.y0, region.y0),
                       std::min(rect.x1, region.x1), std::min(rect.y1, region.y1)});
    again.clear_layers();
    again.add_layers(world.layers(static_cast<int>(last.layer)).name());
    requests.insert(requests.begin(), again);
    return requests;
  };
  const Resume forgets_filter = [](const v1::StreamPointsRequest& request,
                                   const v1::DescribeWorldResponse& world,
                                   client::StreamPosition last) {
    v1::StreamPointsRequest unfiltered = request;
    unfiltered.clear_layers();
    std::vector<v1::StreamPointsRequest> requests = CorrectResume(unfiltered, world, last);
    return requests;
  };
  const Resume world_regions = [](const v1::StreamPointsRequest& request,
                                  const v1::DescribeWorldResponse& world,
                                  client::StreamPosition last) {
    v1::DescribeWorldResponse same_sides = world;
    for (v1::LayerDescription& layer : *same_sides.mutable_layers()) {
      layer.set_region_side(world.region_side());
    }
    return CorrectResume(request, same_sides, last);
  };
  const World world = ConstantForest();
  EXPECT_GT(WrongLayeredResumes(world, repeats_last, 12, 99), 8);
  EXPECT_GT(WrongLayeredResumes(world, forgets_filter, 12, 99), 0);
  EXPECT_GT(WrongLayeredResumes(world, world_regions, 12, 99), 0);
}

}  // namespace
}  // namespace scallop
