// End to end: layered worlds (issue 19) through scallopd. A YAML config names a forest of three
// layers: trees (constant), bushes (a noise field) and rocks (a raster whose road column masks
// them), with one exclusion given; this test builds the same world from the same YAML with the
// core and compares. Checked: DescribeWorld lists the layers with their geometry and D; GetPoints
// pages (packed and encoded, with and without a layer filter) equal PlaneEngine::Points of the
// world and mask, layer by layer with each point's layer; StreamPoints' chunks concatenate to
// the same, one layer's region each; Follow sends every point of the viewports' union once, with
// its layer; Nearest per layer equals a brute force over that layer's points; Verify passes with
// the layered verifier's report; a one-layer world's points are the plain world's, and a plain
// world's answer carries no layers; bad layer names are INVALID_ARGUMENT naming the field.
#include <gtest/gtest.h>
#include <png.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "follow_client.h"
#include "raster_catalog.h"
#include "scallop/plane/world_layers.h"
#include "tests/e2e/scallopd_process.h"
#include "tests/test_png.h"
#include "world_messages.h"
#include "world_yaml.h"

namespace scallop::testing {
namespace {

std::string Dir() { return ::testing::TempDir(); }

// 40 x 30 pixels of side 1 from (-20, -15), value 255 but for column 20 (x in [0, 1)), masked:
// a straight road the rocks keep off.
void WriteRoad(const std::string& path) {
  std::vector<uint8_t> bytes;
  for (int row = 0; row < 30; ++row) {
    for (int column = 0; column < 40; ++column) bytes.push_back(column == 20 ? 0 : 255);
  }
  test_png::WritePng(path, 40, 30, 8, PNG_COLOR_TYPE_GRAY, bytes);
}

constexpr char kForest[] = R"(seed: 7
layers:
  - {name: trees, min_distance: 8}
  - {name: bushes, radius_field: {noise: {r_min: 2.5, r_max: 3.5, frequency: 0.02, noise_seed: 3}}}
  - {name: rocks, radius_field: {raster: {raster_name: road, origin_x: -20, origin_y: -15, pixel_size: 1, r_min: 1.5, r_max: 1.5}}}
exclusions:
  - {first: rocks, second: trees, distance: 2.5}
)";

class E2eLayeredWorldTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    WriteRoad(Dir() + "/e2e_layered_world_test_road.png");
    const std::string config = Dir() + "/e2e_layered_world_test.yaml";
    std::ofstream out(config);
    out << "rasters:\n  road: e2e_layered_world_test_road.png\nworlds:\n  forest:\n";
    std::istringstream lines(kForest);
    for (std::string line; std::getline(lines, line);) out << "    " << line << '\n';
    out << "  one: {seed: 5, layers: [{name: only, min_distance: 1}]}\n"
        << "  plain: {seed: 5, min_distance: 1}\n";
    out.close();
    server_ = ScallopdProcess::Start({"--config", config}).release();
    RasterCatalog rasters;
    ASSERT_TRUE(rasters.Load("road", Dir() + "/e2e_layered_world_test_road.png", "road").ok());
    StatusOr<World> world = WorldFromYaml(YAML::Load(kForest), rasters, "forest");
    ASSERT_TRUE(world.ok()) << world.status().message();
    forest_ = new World(*world);
  }
  static void TearDownTestSuite() {
    delete server_;
    delete forest_;
  }
  void SetUp() override {
    ASSERT_NE(server_, nullptr);
    ASSERT_NE(forest_, nullptr);
  }

  // The core's answer: the world's points in `rect` of the layers in `mask`.
  static PlanePoints Expected(const Rect& rect, LayerMask mask = kAllLayers) {
    PlaneEngine engine({});
    StatusOr<PlanePoints> points = engine.Points(*forest_, rect, mask);
    EXPECT_TRUE(points.ok()) << points.status().message();
    return *points;
  }

  static PlanePoints Get(const Rect& rect, int page_size, const std::vector<std::string>& layers,
                         v1::PointEncoding encoding = v1::POINT_ENCODING_UNSPECIFIED,
                         std::vector<double>* radii = nullptr) {
    v1::GetPointsRequest request;
    request.set_world_name("forest");
    *request.mutable_rect() = RectToMessage(rect);
    request.set_page_size(page_size);
    request.set_encoding(encoding);
    for (const std::string& name : layers) request.add_layers(name);
    PlanePoints points;
    const grpc::Status status = server_->Client().GetAllPoints(request, points, {}, radii);
    EXPECT_TRUE(status.ok()) << status.error_message();
    return points;
  }

  static inline ScallopdProcess* server_ = nullptr;
  static inline World* forest_ = nullptr;
  static constexpr Rect kRect{-20.0, -15.0, 20.0, 15.0};
};

void ExpectSame(const PlanePoints& got, const PlanePoints& expected) {
  ASSERT_EQ(got.ids, expected.ids);
  ASSERT_EQ(got.positions, expected.positions);
  ASSERT_EQ(got.layers, expected.layers);
}

TEST_F(E2eLayeredWorldTest, DescribeWorldListsTheLayersAndTheirGeometry) {
  v1::DescribeWorldRequest request;
  request.set_world_name("forest");
  v1::DescribeWorldResponse world;
  ASSERT_TRUE(server_->Client().DescribeWorld(request, world).ok());
  EXPECT_EQ(world.fingerprint(), forest_->fingerprint());
  ASSERT_EQ(world.layers_size(), 3);
  const WorldLayers& layers = *forest_->layers();
  const char* kinds[] = {"constant", "noise", "raster"};
  for (int k = 0; k < 3; ++k) {
    const v1::LayerDescription& layer = world.layers(k);
    EXPECT_EQ(layer.name(), layers.name(k));
    EXPECT_EQ(layer.field_kind(), kinds[k]);
    EXPECT_EQ(layer.region_side(), RegionLayout(layers.world(k)).side());
    EXPECT_EQ(layer.fingerprint(), layers.world(k).fingerprint());
    ASSERT_EQ(layer.exclusions_size(), 3);
    for (int b = 0; b < 3; ++b) EXPECT_EQ(layer.exclusions(b), layers.exclusion(k, b));
  }
  EXPECT_EQ(world.layers(0).generation_position(), 0u);
  EXPECT_EQ(world.layers(2).exclusions(0), 2.5);
  // The answer lists every pair's D; sent back inline it is the same world.
  EXPECT_EQ(world.world().exclusions_size(), 3);
  v1::DescribeWorldRequest again;
  *again.mutable_world() = world.world();
  v1::DescribeWorldResponse echoed;
  ASSERT_TRUE(server_->Client().DescribeWorld(again, echoed).ok());
  EXPECT_EQ(echoed.fingerprint(), world.fingerprint());
  v1::GetServerInfoResponse info;
  ASSERT_TRUE(server_->Client().GetServerInfo(info).ok());
  EXPECT_EQ(info.max_layers(), kMaxLayers);
}

TEST_F(E2eLayeredWorldTest, PagesAndFiltersEqualTheCore) {
  const PlanePoints all = Expected(kRect);
  ASSERT_GT(all.ids.size(), 100u);
  for (const int layer : {0, 1, 2}) {
    EXPECT_NE(std::count(all.layers.begin(), all.layers.end(), layer), 0) << layer;
  }
  // The road column holds no rock.
  for (size_t k = 0; k < all.ids.size(); ++k) {
    if (all.layers[k] == 2) {
      EXPECT_FALSE(all.positions[k].x >= 0 && all.positions[k].x < 1);
    }
  }
  std::vector<double> radii;
  ExpectSame(Get(kRect, 37, {}, v1::POINT_ENCODING_UNSPECIFIED, &radii), all);
  // A field layer in the world: every point carries its spacing in its layer.
  ASSERT_EQ(radii.size(), all.ids.size());
  for (size_t k = 0; k < all.ids.size(); ++k) {
    ASSERT_EQ(radii[k], forest_->layers()->world(all.layers[k]).SpacingAt(all.positions[k]));
  }
  ExpectSame(Get(kRect, 0, {}, v1::POINT_ENCODING_EXACT), all);
  // A filter, in any order, is the unfiltered answer filtered; pages cross layers.
  ExpectSame(Get(kRect, 13, {"rocks", "trees"}), Expected(kRect, 0b101));
  ExpectSame(Get(kRect, 7, {"bushes"}, v1::POINT_ENCODING_EXACT), Expected(kRect, 0b010));
  // Random rectangles of the world, paged, against the core.
  uint64_t state = 19;
  const auto next = [&] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) * 0x1.0p-53;
  };
  for (int trial = 0; trial < 6; ++trial) {
    const double x = -60 + 100 * next(), y = -60 + 100 * next();
    const Rect rect{x, y, x + 5 + 30 * next(), y + 5 + 30 * next()};
    const auto mask = static_cast<LayerMask>(1 + trial % 7);
    std::vector<std::string> names;
    for (int k = 0; k < 3; ++k) {
      if ((mask >> k) & 1) names.push_back(forest_->layers()->name(k));
    }
    SCOPED_TRACE(trial);
    ExpectSame(Get(rect, 1 + trial * 11, names), Expected(rect, mask));
  }
}

TEST_F(E2eLayeredWorldTest, AStreamIsThePagesOneLayersRegionAChunk) {
  v1::StreamPointsRequest request;
  request.set_world_name("forest");
  *request.mutable_rect() = RectToMessage(kRect);
  PlanePoints streamed;
  std::vector<std::tuple<uint32_t, int64_t, int64_t>> chunks;
  const grpc::Status status = server_->Client().StreamPoints(
      request,
      [&](const v1::PointsChunk& chunk) {
        chunks.emplace_back(chunk.layer(), chunk.region_j(), chunk.region_i());
        for (const uint32_t layer : chunk.points().layers()) EXPECT_EQ(layer, chunk.layer());
        return ReadPoints(chunk.points(), streamed).ok();
      },
      {});
  ASSERT_TRUE(status.ok()) << status.error_message();
  ExpectSame(streamed, Expected(kRect));
  // Layer by layer, each layer's regions by row then column.
  EXPECT_TRUE(std::is_sorted(chunks.begin(), chunks.end()));
  request.add_layers("bushes");
  request.set_encoding(v1::POINT_ENCODING_QUANTISED);
  PlanePoints bushes;
  ASSERT_TRUE(server_->Client().StreamAllPoints(request, bushes).ok());
  const PlanePoints expected = Expected(kRect, 0b010);
  ASSERT_EQ(bushes.ids, expected.ids);
  ASSERT_EQ(bushes.layers, expected.layers);
}

TEST_F(E2eLayeredWorldTest, FollowSendsEveryPointOfTheViewportsOnceWithItsLayer) {
  client::ScallopClient client = server_->Client();
  client::FollowSession session(client);
  std::map<std::pair<int, uint64_t>, Vec2> received;
  const Rect viewports[] = {{-20, -15, 0, 5}, {-10, -15, 10, 5}, {-5, -10, 15, 10}};
  for (int step = 0; step < 3; ++step) {
    v1::FollowRequest request;
    if (step == 0) request.set_world_name("forest");
    *request.mutable_viewport() = RectToMessage(viewports[step]);
    request.set_keep_margin(100);  // nothing evicted: each point comes once
    const grpc::Status status = session.Update(request, [&](const v1::FollowResponse& response) {
      EXPECT_EQ(response.evicted_size(), 0);
      PlanePoints chunk;
      ASSERT_TRUE(ReadPoints(response.chunk().points(), chunk).ok());
      for (size_t k = 0; k < chunk.ids.size(); ++k) {
        EXPECT_EQ(chunk.layers[k], response.chunk().layer());
        EXPECT_TRUE(
            received.emplace(std::pair{int{chunk.layers[k]}, chunk.ids[k]}, chunk.positions[k])
                .second)
            << "sent twice: layer " << int{chunk.layers[k]} << " id " << chunk.ids[k];
      }
    });
    ASSERT_TRUE(status.ok()) << status.error_message();
  }
  ASSERT_TRUE(session.Finish().ok());
  // The union of the viewports, point by point.
  std::map<std::pair<int, uint64_t>, Vec2> expected;
  for (const Rect& viewport : viewports) {
    const PlanePoints points = Expected(viewport);
    for (size_t k = 0; k < points.ids.size(); ++k) {
      expected.emplace(std::pair{int{points.layers[k]}, points.ids[k]}, points.positions[k]);
    }
  }
  EXPECT_EQ(received, expected);
}

TEST_F(E2eLayeredWorldTest, NearestPerLayerEqualsABruteForceOverThatLayer) {
  // Brute force over each layer's points of a square that holds every answer (F2 stays within a
  // few of the layer's spacings, the earlier layers' exclusion disks included).
  const Rect square{-40, -35, 40, 35};
  const PlanePoints all = Expected(square);
  v1::NearestRequest request;
  request.set_world_name("forest");
  uint64_t state = 5;
  const auto next = [&] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) * 0x1.0p-53;
  };
  std::vector<Vec2> positions;
  for (int k = 0; k < 200; ++k) positions.push_back({-18 + 36 * next(), -13 + 26 * next()});
  positions.push_back({0.5, 0.0});  // on the road, where rocks are masked
  for (const Vec2& p : positions) {
    request.mutable_positions()->add_xs(p.x);
    request.mutable_positions()->add_ys(p.y);
  }
  for (int layer = 0; layer < 3; ++layer) {
    request.set_layer(forest_->layers()->name(layer));
    v1::NearestResponse response;
    const grpc::Status status = server_->Client().Nearest(request, response);
    ASSERT_TRUE(status.ok()) << status.error_message();
    ASSERT_EQ(response.ids_size(), static_cast<int>(positions.size()));
    for (size_t k = 0; k < positions.size(); ++k) {
      // Nearest by (squared distance in doubles, id), as the API defines ties.
      std::pair<double, uint64_t> best{INFINITY, 0}, second{INFINITY, 0};
      for (size_t q = 0; q < all.ids.size(); ++q) {
        if (all.layers[q] != layer) continue;
        const double dx = positions[k].x - all.positions[q].x;
        const double dy = positions[k].y - all.positions[q].y;
        const std::pair<double, uint64_t> candidate{dx * dx + dy * dy, all.ids[q]};
        if (candidate < best) {
          second = best;
          best = candidate;
        } else if (candidate < second) {
          second = candidate;
        }
      }
      ASSERT_EQ(response.ids(static_cast<int>(k)), best.second) << "layer " << layer << " " << k;
      ASSERT_EQ(response.f1(static_cast<int>(k)), std::sqrt(best.first));
      ASSERT_EQ(response.f2(static_cast<int>(k)), std::sqrt(second.first));
    }
  }
  // NoiseGrid of a layer agrees with Nearest of that layer.
  v1::NoiseGridRequest grid;
  grid.set_world_name("forest");
  grid.set_layer("bushes");
  grid.set_origin_x(-10);
  grid.set_origin_y(-5);
  grid.set_step(0.75);
  grid.set_width(16);
  grid.set_height(8);
  grid.set_channel(v1::NOISE_CHANNEL_ID);
  v1::NoiseGridResponse image;
  ASSERT_TRUE(server_->Client().NoiseGrid(grid, image).ok());
  v1::NearestRequest samples;
  samples.set_world_name("forest");
  samples.set_layer("bushes");
  for (int r = 0; r < 8; ++r) {
    for (int c = 0; c < 16; ++c) {
      samples.mutable_positions()->add_xs(-10 + c * 0.75);
      samples.mutable_positions()->add_ys(-5 + r * 0.75);
    }
  }
  v1::NearestResponse nearest;
  ASSERT_TRUE(server_->Client().Nearest(samples, nearest).ok());
  ASSERT_EQ(image.ids_size(), nearest.ids_size());
  for (int k = 0; k < image.ids_size(); ++k) EXPECT_EQ(image.ids(k), nearest.ids(k));
}

TEST_F(E2eLayeredWorldTest, VerifyJudgesEveryLayer) {
  v1::VerifyRequest request;
  request.set_world_name("forest");
  *request.mutable_rect() = RectToMessage({-12, -10, 12, 10});
  v1::VerifyResponse response;
  const grpc::Status status = server_->Client().Verify(request, response);
  ASSERT_TRUE(status.ok()) << status.error_message();
  EXPECT_TRUE(response.passed());
  ASSERT_EQ(response.layered().layers_size(), 3);
  int64_t points = 0;
  for (int k = 0; k < 3; ++k) {
    const v1::LayerVerifyResponse& layer = response.layered().layers(k);
    EXPECT_EQ(layer.name(), forest_->layers()->name(k));
    EXPECT_TRUE(layer.report().passed()) << layer.name();
    EXPECT_EQ(layer.report().conflicts(), 0);
    points += layer.points_checked();
  }
  EXPECT_EQ(points, static_cast<int64_t>(Expected({-12, -10, 12, 10}).ids.size()));
  EXPECT_EQ(response.layered().cross_conflicts(), 0);
  EXPECT_GT(response.layered().cross_pairs_checked(), 0);
  EXPECT_GE(response.layered().min_cross_ratio(), 1.0);
}

TEST_F(E2eLayeredWorldTest, OldClientsSeeOneLayerAndPlainWorldsAsBefore) {
  // A plain world's answer is what the packed appender wrote before layers: no layers field.
  v1::GetPointsRequest request;
  request.set_world_name("plain");
  *request.mutable_rect() = RectToMessage(kRect);
  v1::GetPointsResponse plain;
  ASSERT_TRUE(server_->Client().GetPoints(request, plain).ok());
  EXPECT_EQ(plain.points().layers_size(), 0);
  PlaneEngine engine({});
  const StatusOr<World> world = World::Create({.seed = 5});
  ASSERT_TRUE(world.ok());
  const StatusOr<PlanePoints> points = engine.Points(*world, kRect);
  ASSERT_TRUE(points.ok());
  v1::Points before;
  AppendPoints(*points, 0, points->ids.size(), before);
  EXPECT_EQ(plain.points().SerializeAsString(), before.SerializeAsString());
  // A one-layer world holds the plain world's points and ids, each of layer 0.
  request.set_world_name("one");
  v1::GetPointsResponse one;
  ASSERT_TRUE(server_->Client().GetPoints(request, one).ok());
  v1::Points without_layers = one.points();
  ASSERT_EQ(without_layers.layers_size(), without_layers.ids_size());
  for (const uint32_t layer : without_layers.layers()) EXPECT_EQ(layer, 0u);
  without_layers.clear_layers();
  EXPECT_EQ(without_layers.SerializeAsString(), before.SerializeAsString());
}

TEST_F(E2eLayeredWorldTest, BadLayerNamesAreInvalidArgumentNamingTheField) {
  v1::GetPointsRequest request;
  request.set_world_name("forest");
  *request.mutable_rect() = RectToMessage(kRect);
  request.add_layers("ferns");
  v1::GetPointsResponse response;
  grpc::Status status = server_->Client().GetPoints(request, response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_TRUE(status.error_message().starts_with("layers: no layer named 'ferns'"))
      << status.error_message();
  request.set_world_name("plain");
  status = server_->Client().GetPoints(request, response);
  EXPECT_TRUE(status.error_message().starts_with("layers: the world has no layers"))
      << status.error_message();
  // A page token is bound to its filter.
  request.set_world_name("forest");
  request.clear_layers();
  request.set_page_size(5);
  ASSERT_TRUE(server_->Client().GetPoints(request, response).ok());
  request.set_page_token(response.next_page_token());
  request.add_layers("trees");
  status = server_->Client().GetPoints(request, response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_TRUE(status.error_message().starts_with("page_token:")) << status.error_message();

  v1::NearestRequest nearest;
  nearest.set_world_name("forest");
  nearest.mutable_positions()->add_xs(0);
  nearest.mutable_positions()->add_ys(0);
  v1::NearestResponse answer;
  status = server_->Client().Nearest(nearest, answer);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_TRUE(status.error_message().starts_with("layer: required")) << status.error_message();
  // An inline world's bad layer names its field.
  v1::World bad;
  bad.set_seed(1);
  bad.set_algorithm(v1::ALGORITHM_A3);
  bad.add_layers()->set_name("a");
  bad.mutable_layers(0)->set_min_distance(1);
  bad.add_layers()->set_name("b");
  bad.mutable_layers(1)->set_min_distance(2);
  bad.add_exclusions()->set_first("a");
  bad.mutable_exclusions(0)->set_second("c");
  v1::DescribeWorldRequest describe;
  *describe.mutable_world() = bad;
  v1::DescribeWorldResponse described;
  status = server_->Client().DescribeWorld(describe, described);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_TRUE(status.error_message().starts_with("world.exclusions[0].second"))
      << status.error_message();
}

}  // namespace
}  // namespace scallop::testing
