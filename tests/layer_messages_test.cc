// Layered worlds through the API's messages (issue 19): a layered world round-trips (every
// pair's D listed in answers, the same fingerprint read back), bad layers and exclusions are
// named world.layers[k]... and world.exclusions[n]..., and a layered world's points keep their
// layer through the packed arrays and both compact encodings, layer by layer with each layer's
// own region geometry. A plain world's packed and encoded messages are the bytes the appenders
// wrote before layers (no layers field, no encoded.layers), and a malformed layer is refused.
#include <gtest/gtest.h>

#include <vector>

#include "encoded_points.h"
#include "scallop/plane/layer_regions.h"
#include "scallop/plane/world_layers.h"
#include "world_messages.h"

namespace scallop {
namespace {

v1::World ForestMessage() {
  v1::World message;
  message.set_seed(7);
  message.set_algorithm(v1::ALGORITHM_A3);
  const std::pair<const char*, double> layers[] = {{"trees", 8}, {"bushes", 3}, {"rocks", 1.5}};
  for (const auto& [name, d] : layers) {
    v1::Layer& layer = *message.add_layers();
    layer.set_name(name);
    layer.set_min_distance(d);
  }
  v1::NoiseRadiusField& noise = *message.mutable_layers(1)->mutable_radius_field()->mutable_noise();
  noise.set_r_min(2.5);
  noise.set_r_max(3.5);
  noise.set_frequency(0.02);
  v1::LayerExclusion& exclusion = *message.add_exclusions();
  exclusion.set_first("rocks");
  exclusion.set_second("trees");
  exclusion.set_distance(2.5);
  return message;
}

TEST(LayerMessagesTest, ALayeredWorldRoundTripsWithEveryPairsDistance) {
  StatusOr<World> world = WorldFromMessage(ForestMessage());
  ASSERT_TRUE(world.ok()) << world.status().message();
  const WorldLayers& layers = *world->layers();
  ASSERT_EQ(layers.count(), 3);
  EXPECT_EQ(layers.exclusion(2, 0), 2.5);
  EXPECT_TRUE(layers.world(1).radius_field() != nullptr);
  const v1::World answer = WorldToMessage(*world);
  ASSERT_EQ(answer.layers_size(), 3);
  EXPECT_TRUE(answer.layers(1).radius_field().has_noise());
  EXPECT_FALSE(answer.layers(2).has_radius_field());
  ASSERT_EQ(answer.exclusions_size(), 3);  // (trees, bushes), (trees, rocks), (bushes, rocks)
  EXPECT_EQ(answer.exclusions(1).first(), "trees");
  EXPECT_EQ(answer.exclusions(1).second(), "rocks");
  EXPECT_EQ(answer.exclusions(1).distance(), 2.5);
  EXPECT_EQ(answer.exclusions(0).distance(), layers.exclusion(0, 1));
  StatusOr<World> again = WorldFromMessage(answer);
  ASSERT_TRUE(again.ok()) << again.status().message();
  EXPECT_EQ(again->fingerprint(), world->fingerprint());
  EXPECT_EQ(*again, *world);
  // A spec as a client sends it: the exclusions as given.
  const v1::World sent = WorldToMessage(world->spec());
  EXPECT_EQ(sent.layers_size(), 3);
}

TEST(LayerMessagesTest, BadLayersAndExclusionsNameTheirField) {
  const auto error_of = [](const v1::World& message) {
    StatusOr<World> world = WorldFromMessage(message);
    EXPECT_FALSE(world.ok());
    return world.ok() ? std::string() : world.status().message();
  };
  v1::World message = ForestMessage();
  message.mutable_layers(2)->set_name("trees");
  EXPECT_TRUE(error_of(message).starts_with("world.layers[2].name")) << error_of(message);
  message = ForestMessage();
  message.mutable_layers(1)->mutable_radius_field()->mutable_noise()->set_frequency(5);
  EXPECT_TRUE(error_of(message).starts_with("world.layers[1].radius_field.noise.frequency"))
      << error_of(message);
  message = ForestMessage();
  message.mutable_layers(1)->mutable_radius_field()->mutable_raster()->set_raster_name("x");
  EXPECT_TRUE(error_of(message).starts_with("world.layers[1].radius_field.raster.raster_name"))
      << error_of(message);
  message = ForestMessage();
  message.mutable_exclusions(0)->set_distance(-1);
  EXPECT_TRUE(error_of(message).starts_with("world.exclusions[0].distance")) << error_of(message);
  message = ForestMessage();
  message.mutable_exclusions(0)->set_second("ferns");
  EXPECT_TRUE(error_of(message).starts_with("world.exclusions[0].second")) << error_of(message);
  message = ForestMessage();
  *message.add_exclusions() = message.exclusions(0);
  message.mutable_exclusions(1)->set_first("trees");
  message.mutable_exclusions(1)->set_second("rocks");
  message.mutable_exclusions(1)->set_distance(3);
  EXPECT_TRUE(error_of(message).starts_with("world.exclusions[1]")) << error_of(message);
  message = ForestMessage();
  message.mutable_radius_field()->mutable_noise()->set_r_min(1);
  EXPECT_TRUE(error_of(message).starts_with("world.radius_field")) << error_of(message);
}

// The world's points of `rect`, each with its layer, as a server writes them in `encoding`
// (layer by layer, StartLayer before each), read back.
PlanePoints ThroughMessage(const World& world, const PlanePoints& points, PointEncoding encoding,
                           std::vector<double>* radii = nullptr) {
  v1::Points message;
  AppendPoints(points, 0, points.ids.size(), message, world, encoding);
  PlanePoints read;
  const Status status = ReadPoints(message, read, radii);
  EXPECT_TRUE(status.ok()) << status.message();
  return read;
}

TEST(LayerMessagesTest, PointsKeepTheirLayerInEveryEncoding) {
  StatusOr<World> world = WorldFromMessage(ForestMessage());
  ASSERT_TRUE(world.ok());
  PlaneEngine engine({});
  const Rect rect{-37.5, -20.25, 41, 33};
  StatusOr<PlanePoints> points = engine.Points(*world, rect);
  ASSERT_TRUE(points.ok());
  ASSERT_GT(points->ids.size(), 300u);
  for (const PointEncoding encoding : {PointEncoding::kPacked, PointEncoding::kExact}) {
    std::vector<double> radii;
    const PlanePoints read = ThroughMessage(*world, *points, encoding, &radii);
    EXPECT_EQ(read.ids, points->ids);
    EXPECT_EQ(read.positions, points->positions);
    EXPECT_EQ(read.layers, points->layers);
    // A noise layer: every point carries its spacing in its layer.
    ASSERT_EQ(radii.size(), points->ids.size());
    for (size_t k = 0; k < radii.size(); ++k) {
      EXPECT_EQ(radii[k],
                world->layers()->world(points->layers[k]).SpacingAt(points->positions[k]));
    }
  }
  // Quantised: the layers and ids exact, each point within its own layer's quantum.
  const PlanePoints quantised = ThroughMessage(*world, *points, PointEncoding::kQuantised);
  EXPECT_EQ(quantised.ids, points->ids);
  EXPECT_EQ(quantised.layers, points->layers);
  for (size_t k = 0; k < quantised.ids.size(); ++k) {
    const double side = RegionLayout(world->layers()->world(points->layers[k])).side();
    EXPECT_LE(std::abs(quantised.positions[k].x - points->positions[k].x), side * 0x1p-16);
    EXPECT_LE(std::abs(quantised.positions[k].y - points->positions[k].y), side * 0x1p-16);
  }
  // Encoded: the layer once per region, no per-point layers, and no header a decoder that knows
  // no layers could misread.
  v1::Points message;
  AppendPoints(*points, 0, points->ids.size(), message, *world, PointEncoding::kExact);
  EXPECT_EQ(message.layers_size(), 0);
  EXPECT_EQ(message.encoded().region_side(), 0.0);
  ASSERT_EQ(message.encoded().layers_size(), 3);
  EXPECT_EQ(message.encoded().layers(2).region_side(),
            RegionLayout(world->layers()->world(2)).side());
  // A region naming a layer the message lacks is refused, naming it.
  message.mutable_encoded()->mutable_regions(0)->set_layer(3);
  PlanePoints read;
  const Status status = ReadPoints(message, read);
  EXPECT_TRUE(status.message().starts_with("encoded.regions[0].layer")) << status.message();
  EXPECT_TRUE(read.ids.empty());
}

TEST(LayerMessagesTest, PlainWorldsMessagesAreTheBytesOfBeforeLayers) {
  const World world = *World::Create({.seed = 3});
  PlaneEngine engine({});
  const Rect rect{-20, -20, 20, 20};
  const PlanePoints points = *engine.Points(world, rect);
  // Packed: the appender that took a field (the one before layers) and the one that takes the
  // world write the same bytes.
  v1::Points before, now;
  AppendPoints(points, 0, points.ids.size(), before, world.radius_field());
  AppendPoints(points, 0, points.ids.size(), now, world, PointEncoding::kPacked);
  EXPECT_EQ(now.SerializeAsString(), before.SerializeAsString());
  EXPECT_EQ(now.layers_size(), 0);
  // Encoded: no layers, every region's layer 0 (not written), the header as before.
  v1::Points encoded;
  AppendPoints(points, 0, points.ids.size(), encoded, world, PointEncoding::kExact);
  EXPECT_EQ(encoded.encoded().layers_size(), 0);
  EXPECT_EQ(encoded.encoded().region_side(), 16.0);
  for (const v1::EncodedRegion& region : encoded.encoded().regions()) {
    EXPECT_EQ(region.layer(), 0u);
  }
  PlanePoints read;
  ASSERT_TRUE(ReadPoints(encoded, read).ok());
  EXPECT_TRUE(read.layers.empty());
  // A plain world's encoded region may not name a layer.
  encoded.mutable_encoded()->mutable_regions(0)->set_layer(1);
  EXPECT_TRUE(ReadPoints(encoded, read).message().starts_with("encoded.regions[0].layer"));
  // Packed arrays with a layers array of the wrong length are refused.
  v1::Points bad = now;
  bad.add_layers(0);
  EXPECT_TRUE(ReadPoints(bad, read).message().starts_with("points: layers"));
}

TEST(LayerMessagesTest, VisitLayerPointsPagesAcrossLayers) {
  StatusOr<World> world = WorldFromMessage(ForestMessage());
  ASSERT_TRUE(world.ok());
  PlaneEngine engine({});
  const Rect rect{-30, -30, 30, 30};
  const PlanePoints all = *engine.Points(*world, rect, 0b110);
  StatusOr<std::vector<LayerRegions>> parts = QueryRegions(engine, *world, rect, 0b110);
  ASSERT_TRUE(parts.ok());
  ASSERT_EQ(parts->size(), 2u);
  // Pages of every size, joined, are the whole answer, with the layer each part started.
  for (const size_t page : {size_t{1}, size_t{7}, size_t{64}, all.ids.size()}) {
    PlanePoints joined;
    for (size_t begin = 0; begin < all.ids.size(); begin += page) {
      int layer = -1;
      const size_t total = VisitLayerPoints(
          *parts, rect, begin, begin + page, [&](const LayerRegions& part) { layer = part.layer; },
          [&](Vec2 position, uint64_t id) {
            joined.positions.push_back(position);
            joined.ids.push_back(id);
            joined.layers.push_back(static_cast<uint8_t>(layer));
          });
      ASSERT_EQ(total, all.ids.size());
    }
    EXPECT_EQ(joined.ids, all.ids) << page;
    EXPECT_EQ(joined.positions, all.positions) << page;
    EXPECT_EQ(joined.layers, all.layers) << page;
  }
}

}  // namespace
}  // namespace scallop
