// End to end: radius-field worlds through scallopd. Two servers read one YAML config that
// loads a raster (a PNG made here, with a masked column) and names a raster world and a noise
// world. Checked: ServerInfo and DescribeWorld report the field and the raster; the points of
// the named raster world are the same on both servers, carry R (the brute force evaluates the
// field from the same file), keep the max rule pairwise and stay out of the mask; pages, streams
// and an inline copy of the world give the same points; Nearest agrees with a brute force over
// those points and NoiseGrid with Nearest, on both servers; bad fields are INVALID_ARGUMENT
// naming the message's field.
#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "raster_catalog.h"
#include "scallop/field/raster_png.h"
#include "tests/e2e/scallopd_process.h"
#include "tests/test_png.h"
#include "world_messages.h"

namespace scallop::testing {
namespace {

// 12 x 8 pixels of side 4 from (-24, -16): values rise by 2 a pixel (slope 2/254 / 4 of the
// range); column 2 is masked.
constexpr int kWidth = 12, kHeight = 8;
constexpr double kPixel = 4.0, kOriginX = -24.0, kOriginY = -16.0, kRMin = 1.0, kRMax = 2.5;

std::string Dir() { return ::testing::TempDir(); }
std::string PngPath() { return Dir() + "/e2e_field_world_test_hills.png"; }

void WriteFiles() {
  std::vector<uint8_t> bytes;
  for (int top = 0; top < kHeight; ++top) {
    const int row = kHeight - 1 - top;
    for (int column = 0; column < kWidth; ++column) {
      bytes.push_back(column == 2 ? 0 : static_cast<uint8_t>(1 + 2 * (column + row)));
    }
  }
  test_png::WritePng(PngPath(), kWidth, kHeight, 8, PNG_COLOR_TYPE_GRAY, bytes);
  std::ofstream config(Dir() + "/e2e_field_world_test.yaml");
  // The raster by a path relative to the config's folder.
  config << "rasters:\n  hills: e2e_field_world_test_hills.png\n"
         << "worlds:\n"
         << "  valley: {seed: 3, radius_field: {raster: {raster_name: hills, origin_x: " << kOriginX
         << ", origin_y: " << kOriginY << ", pixel_size: " << kPixel << ", r_min: " << kRMin
         << ", r_max: " << kRMax << "}}}\n"
         << "  dunes: {seed: 4, radius_field: {noise: {r_min: 0.5, r_max: 2, frequency: 0.02, "
            "noise_seed: 9}}}\n";
}

// The valley world's field, built here from the same file: what R must be at each point.
RadiusField ValleyField() {
  StatusOr<RasterImage> image = LoadGrayscalePng(PngPath());
  EXPECT_TRUE(image.ok()) << image.status().message();
  RadiusFieldSpec spec;
  spec.kind = RadiusFieldKind::kRaster;
  spec.raster = std::make_shared<const RasterImage>(*image);
  spec.raster_origin = {kOriginX, kOriginY};
  spec.pixel_size = kPixel;
  spec.r_min = kRMin;
  spec.r_max = kRMax;
  return *RadiusField::Create(spec);
}

v1::World InlineValley() {
  v1::World world;
  world.set_seed(3);
  world.set_algorithm(v1::ALGORITHM_A3);
  v1::RasterRadiusField& raster = *world.mutable_radius_field()->mutable_raster();
  raster.set_raster_name("hills");
  raster.set_origin_x(kOriginX);
  raster.set_origin_y(kOriginY);
  raster.set_pixel_size(kPixel);
  raster.set_r_min(kRMin);
  raster.set_r_max(kRMax);
  return world;
}

struct FieldPoints {
  PlanePoints points;
  std::vector<double> radii;
};

class E2eFieldWorldTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    WriteFiles();
    const std::string config = Dir() + "/e2e_field_world_test.yaml";
    first_ = ScallopdProcess::Start({"--config", config}).release();
    second_ = ScallopdProcess::Start({"--config", config, "--threads", "1"}).release();
  }
  static void TearDownTestSuite() {
    delete first_;
    delete second_;
  }
  void SetUp() override {
    ASSERT_NE(first_, nullptr);
    ASSERT_NE(second_, nullptr);
  }

  // Every point of `rect` of the world named `name` (or `inline_world`), paged by `page_size`.
  static FieldPoints Get(const ScallopdProcess& server, const Rect& rect, int page_size = 0,
                         const v1::World* inline_world = nullptr,
                         const std::string& name = "valley") {
    v1::GetPointsRequest request;
    if (inline_world != nullptr) {
      *request.mutable_world() = *inline_world;
    } else {
      request.set_world_name(name);
    }
    *request.mutable_rect() = RectToMessage(rect);
    request.set_page_size(page_size);
    FieldPoints out;
    const grpc::Status status = server.Client().GetAllPoints(request, out.points, {}, &out.radii);
    EXPECT_TRUE(status.ok()) << status.error_message();
    return out;
  }

  static inline ScallopdProcess* first_ = nullptr;
  static inline ScallopdProcess* second_ = nullptr;
  static constexpr Rect kRect{-30.0, -20.0, 30.0, 20.0};
};

void ExpectSame(const FieldPoints& a, const FieldPoints& b) {
  ASSERT_EQ(a.points.ids, b.points.ids);
  ASSERT_EQ(a.points.positions, b.points.positions);
  ASSERT_EQ(a.radii, b.radii);
}

TEST_F(E2eFieldWorldTest, ServerInfoAndDescribeWorldReportTheFieldAndTheRaster) {
  v1::GetServerInfoResponse info;
  ASSERT_TRUE(first_->Client().GetServerInfo(info).ok());
  ASSERT_EQ(info.rasters_size(), 1);
  const v1::RasterInfo& raster = info.rasters(0);
  EXPECT_EQ(raster.name(), "hills");
  EXPECT_EQ(raster.width(), kWidth);
  EXPECT_EQ(raster.height(), kHeight);
  EXPECT_EQ(raster.bit_depth(), 8);
  EXPECT_EQ(raster.pixel_hash(), RasterPixelHash(*ValleyField().spec().raster));
  ASSERT_EQ(info.world_descriptions_size(), info.world_names_size());
  for (int k = 0; k < info.world_names_size(); ++k) {
    if (info.world_names(k) == "valley") {
      EXPECT_NE(info.world_descriptions(k).find("field=raster"), std::string::npos);
    }
  }

  v1::DescribeWorldRequest request;
  request.set_world_name("valley");
  v1::DescribeWorldResponse world;
  ASSERT_TRUE(first_->Client().DescribeWorld(request, world).ok());
  EXPECT_EQ(world.field_kind(), "raster");
  EXPECT_EQ(world.r_min(), kRMin);
  EXPECT_EQ(world.r_max(), kRMax);
  EXPECT_EQ(world.raster().name(), "hills");
  EXPECT_EQ(world.world().min_distance(), kRMin);
  EXPECT_EQ(world.world().radius_field().raster().raster_name(), "hills");
  EXPECT_EQ(world.world().radius_field().raster().pixel_hash(), raster.pixel_hash());
  // The answer's world sent back inline is the same world.
  v1::DescribeWorldRequest again;
  *again.mutable_world() = world.world();
  v1::DescribeWorldResponse echoed;
  ASSERT_TRUE(second_->Client().DescribeWorld(again, echoed).ok());
  EXPECT_EQ(echoed.fingerprint(), world.fingerprint());

  request.set_world_name("dunes");
  ASSERT_TRUE(first_->Client().DescribeWorld(request, world).ok());
  EXPECT_EQ(world.field_kind(), "noise");
  EXPECT_EQ(world.world().radius_field().noise().noise_seed(), 9u);
}

TEST_F(E2eFieldWorldTest, NamedRasterWorldIsTheSameOnTwoServersAndKeepsTheRule) {
  const FieldPoints a = Get(*first_, kRect);
  const FieldPoints b = Get(*second_, kRect);
  ExpectSame(a, b);
  ASSERT_GT(a.points.ids.size(), 100u);
  const RadiusField field = ValleyField();
  ASSERT_EQ(a.radii.size(), a.points.positions.size());
  int64_t conflicts = 0, masked = 0, wrong_r = 0;
  for (size_t k = 0; k < a.points.positions.size(); ++k) {
    const Vec2 p = a.points.positions[k];
    if (a.radii[k] != field.Evaluate(p)) ++wrong_r;
    if (field.IsMasked(p)) ++masked;
    for (size_t m = k + 1; m < a.points.positions.size(); ++m) {
      const Vec2 q = a.points.positions[m];
      const double dx = p.x - q.x, dy = p.y - q.y;
      const double spacing = std::max(field.Evaluate(p), field.Evaluate(q));
      if (dx * dx + dy * dy < spacing * spacing) ++conflicts;
    }
  }
  EXPECT_EQ(wrong_r, 0);
  EXPECT_EQ(masked, 0);
  EXPECT_EQ(conflicts, 0);
}

TEST_F(E2eFieldWorldTest, PagesStreamsAndTheInlineWorldGiveTheSamePoints) {
  const FieldPoints whole = Get(*first_, kRect);
  ExpectSame(Get(*second_, kRect, 37), whole);
  const v1::World inline_world = InlineValley();
  ExpectSame(Get(*first_, kRect, 0, &inline_world), whole);

  v1::StreamPointsRequest stream;
  stream.set_world_name("valley");
  *stream.mutable_rect() = RectToMessage(kRect);
  FieldPoints streamed;
  ASSERT_TRUE(first_->Client().StreamAllPoints(stream, streamed.points, {}, &streamed.radii).ok());
  ExpectSame(streamed, whole);

  // The noise world too, across servers.
  ExpectSame(Get(*first_, kRect, 0, nullptr, "dunes"), Get(*second_, kRect, 101, nullptr, "dunes"));
}

// A noise image of the noise world is the same on both servers, and each sample equals
// Nearest at the sample's position (the documented positions, origin + k step).
TEST_F(E2eFieldWorldTest, NoiseGridAgreesAcrossServersAndWithNearest) {
  v1::NoiseGridRequest grid;
  grid.set_world_name("dunes");
  grid.set_origin_x(-10.25);
  grid.set_origin_y(-7.5);
  grid.set_step(0.5);
  grid.set_width(40);
  grid.set_height(30);
  grid.set_channel(v1::NOISE_CHANNEL_F2);
  v1::NoiseGridResponse first, second;
  const grpc::Status status = first_->Client().NoiseGrid(grid, first);
  ASSERT_TRUE(status.ok()) << status.error_message();
  ASSERT_TRUE(second_->Client().NoiseGrid(grid, second).ok());
  ASSERT_EQ(first.values_size(), 40 * 30);
  ASSERT_EQ(second.values_size(), first.values_size());
  v1::NearestRequest nearest;
  nearest.set_world_name("dunes");
  for (int k = 0; k < first.values_size(); ++k) {
    EXPECT_EQ(first.values(k), second.values(k)) << k;
    nearest.mutable_positions()->add_xs(-10.25 + static_cast<double>(k % 40) * 0.5);
    nearest.mutable_positions()->add_ys(-7.5 + static_cast<double>(k / 40) * 0.5);
  }
  v1::NearestResponse answer;
  ASSERT_TRUE(first_->Client().Nearest(nearest, answer).ok());
  for (int k = 0; k < first.values_size(); ++k) EXPECT_EQ(answer.f2(k), first.values(k)) << k;
}

// Nearest on the raster world (its masked column included) against a brute force over the
// points GetPoints serves, on both servers.
TEST_F(E2eFieldWorldTest, NearestAgreesWithBruteForceOverThePoints) {
  const FieldPoints around = Get(*first_, {-40.0, -36.0, 40.0, 36.0});
  v1::NearestRequest request;
  request.set_world_name("valley");
  // The last two inside the masked column [-16, -12) x [-16, 16).
  const std::vector<Vec2> probes{{0.5, 0.5},   {-13.0, 2.0},  {7.25, -9.5},
                                 {20.0, 11.0}, {-14.0, -3.0}, {-15.9, 8.5}};
  for (const Vec2& p : probes) {
    request.mutable_positions()->add_xs(p.x);
    request.mutable_positions()->add_ys(p.y);
  }
  v1::NearestResponse response, again;
  const grpc::Status status = first_->Client().Nearest(request, response);
  ASSERT_TRUE(status.ok()) << status.error_message();
  ASSERT_TRUE(second_->Client().Nearest(request, again).ok());
  for (size_t k = 0; k < probes.size(); ++k) {
    const auto n = static_cast<int>(k);
    double best = INFINITY, second = INFINITY;
    uint64_t id = 0, second_id = 0;
    for (size_t m = 0; m < around.points.positions.size(); ++m) {
      const Vec2 q = around.points.positions[m];
      const double d = std::hypot(q.x - probes[k].x, q.y - probes[k].y);
      if (d < best || (d == best && around.points.ids[m] < id)) {
        second = best;
        second_id = id;
        best = d;
        id = around.points.ids[m];
      } else if (d < second || (d == second && around.points.ids[m] < second_id)) {
        second = d;
        second_id = around.points.ids[m];
      }
    }
    EXPECT_EQ(response.ids(n), id) << k;
    EXPECT_NEAR(response.f1(n), best, 1e-12) << k;
    EXPECT_NEAR(response.f2(n), second, 1e-12) << k;
    EXPECT_EQ(again.ids(n), response.ids(n)) << k;
    EXPECT_EQ(again.f2(n), response.f2(n)) << k;
  }
}

TEST_F(E2eFieldWorldTest, BadFieldsAreInvalidArgumentNamingTheField) {
  struct Case {
    void (*plant)(v1::World&);
    const char* field;
  };
  const Case cases[] = {
      {[](v1::World& w) { w.mutable_radius_field()->mutable_raster()->set_raster_name("x"); },
       "world.radius_field.raster.raster_name"},
      {[](v1::World& w) { w.mutable_radius_field()->mutable_raster()->set_pixel_hash(1); },
       "world.radius_field.raster.pixel_hash"},
      {[](v1::World& w) { w.mutable_radius_field()->mutable_raster()->set_pixel_size(0.01); },
       "world.radius_field.raster.pixel_size"},
      {[](v1::World& w) { w.mutable_radius_field()->mutable_raster()->set_r_min(NAN); },
       "world.radius_field.raster.r_min"},
      {[](v1::World& w) {
         w.mutable_radius_field()->mutable_noise()->set_r_min(1.0);
         w.mutable_radius_field()->mutable_noise()->set_r_max(4.0);
         w.mutable_radius_field()->mutable_noise()->set_frequency(1.0);
       },
       "world.radius_field.noise.frequency"},
      {[](v1::World& w) { w.mutable_radius_field()->Clear(); }, "world.radius_field"},
      {[](v1::World& w) { w.set_algorithm(v1::ALGORITHM_A1); }, "world.algorithm"},
  };
  for (const Case& c : cases) {
    v1::GetPointsRequest request;
    *request.mutable_world() = InlineValley();
    c.plant(*request.mutable_world());
    *request.mutable_rect() = RectToMessage({0.0, 0.0, 4.0, 4.0});
    v1::GetPointsResponse response;
    const grpc::Status status = first_->Client().GetPoints(request, response);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << c.field;
    EXPECT_EQ(status.error_message().rfind(std::string(c.field) + ":", 0), 0u)
        << status.error_message();
  }
}

}  // namespace
}  // namespace scallop::testing
