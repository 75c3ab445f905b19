// End to end: Nearest and NoiseGrid through a real scallopd give the core's
// answers bit for bit (on seams, far out, by a named world), and refuse bad
// batches and grids with the documented codes, naming the field.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdlib>
#include <fstream>

#include "scallop/noise/nearest_lookup.h"
#include "scallop/noise/noise_grid.h"
#include "scallop/random/rng.h"
#include "tests/e2e/scallopd_process.h"
#include "tests/test_worlds.h"
#include "world_messages.h"

namespace scallop::testing {
namespace {

// Small limits, so that the tests reach them cheaply.
constexpr int kBatchLimit = 3000;
constexpr int kSampleLimit = 20000;

bool SameBits(double a, double b) {
  return std::bit_cast<uint64_t>(a) == std::bit_cast<uint64_t>(b);
}

// Entry k of the response equals the core's answer k, doubles to the bit.
::testing::AssertionResult SameAnswers(const std::vector<NearestPoint>& expected,
                                       const v1::NearestResponse& response) {
  const int n = static_cast<int>(expected.size());
  if (response.ids_size() != n || response.f1_size() != n || response.f2_size() != n ||
      response.nearest_xs_size() != n || response.nearest_ys_size() != n ||
      response.cell_values_size() != n) {
    return ::testing::AssertionFailure() << "array sizes differ from " << n;
  }
  for (int k = 0; k < n; ++k) {
    const NearestPoint& e = expected[k];
    if (response.ids(k) != e.id || !SameBits(response.f1(k), e.f1) ||
        !SameBits(response.f2(k), e.f2) || !SameBits(response.nearest_xs(k), e.position.x) ||
        !SameBits(response.nearest_ys(k), e.position.y) ||
        !SameBits(response.cell_values(k), e.cell_value)) {
      return ::testing::AssertionFailure() << "entry " << k << " differs";
    }
  }
  return ::testing::AssertionSuccess();
}

std::vector<Vec2> TestPositions(uint64_t seed) {
  Rng rng(seed);
  std::vector<Vec2> positions;
  for (int k = 0; k < 2000; ++k) positions.push_back({rng.Uniform(-50, 50), rng.Uniform(-50, 50)});
  for (int k = -3; k <= 3; ++k) {
    positions.push_back({16.0 * k, rng.Uniform(-50, 50)});  // on seams
    positions.push_back({16.0 * k, 16.0 * k});              // on corners
  }
  const double limit = 0x1.0p32;
  positions.push_back({limit, -limit});  // on the precision limit
  positions.push_back({-limit + 0.25, 1e9});
  return positions;
}

v1::NearestRequest RequestFor(const WorldSpec& world, const std::vector<Vec2>& positions) {
  v1::NearestRequest request;
  *request.mutable_world() = WorldToMessage(world);
  for (const Vec2& p : positions) {
    request.mutable_positions()->add_xs(p.x);
    request.mutable_positions()->add_ys(p.y);
  }
  return request;
}

class E2eNearestTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    config_path_ = new std::string(::testing::TempDir() + "e2e_nearest_config.yaml");
    std::ofstream(*config_path_) << "max_nearest_batch: " << kBatchLimit
                                 << "\nmax_noise_grid_samples: " << kSampleLimit << "\n";
    server_ =
        ScallopdProcess::Start({"--config", *config_path_, "--world", "coast:7:1:a3"}).release();
  }
  static void TearDownTestSuite() {
    delete server_;
    std::remove(config_path_->c_str());
    delete config_path_;
  }
  void SetUp() override { ASSERT_NE(server_, nullptr); }

  static std::vector<NearestPoint> CoreAnswers(const World& world,
                                               const std::vector<Vec2>& positions) {
    PlaneEngine engine({.threads = 1});
    NearestLookup lookup(engine);
    std::vector<NearestPoint> results(positions.size());
    EXPECT_TRUE(lookup.Nearest(world, positions, results).ok());
    return results;
  }

  static ScallopdProcess* server_;
  static std::string* config_path_;
};
ScallopdProcess* E2eNearestTest::server_ = nullptr;
std::string* E2eNearestTest::config_path_ = nullptr;

TEST_F(E2eNearestTest, AnswersAreTheCoresBitForBit) {
  client::ScallopClient client = server_->Client();
  for (const World& world :
       {ValidWorld({.seed = 7}),
        ValidWorld(
            {.seed = 11, .min_distance = 0.5, .algorithm = WorldAlgorithm::kA1, .density = 1.5})}) {
    std::vector<Vec2> positions = TestPositions(world.seed());
    if (world.min_distance() != 1) {
      for (Vec2& p : positions) p = {p.x * world.min_distance(), p.y * world.min_distance()};
    }
    v1::NearestResponse response;
    const grpc::Status status = client.Nearest(RequestFor(world.spec(), positions), response);
    ASSERT_TRUE(status.ok()) << client::DescribeStatus(status);
    EXPECT_TRUE(SameAnswers(CoreAnswers(world, positions), response)) << world.Describe();
    EXPECT_EQ(response.world().min_distance(), world.min_distance());
  }
}

TEST_F(E2eNearestTest, NamedWorldAnswersAsItsInlineTwin) {
  client::ScallopClient client = server_->Client();
  const std::vector<Vec2> positions = TestPositions(3);
  v1::NearestRequest request = RequestFor(WorldSpec{.seed = 7}, positions);
  request.set_world_name("coast");
  v1::NearestResponse response;
  ASSERT_TRUE(client.Nearest(request, response).ok());
  EXPECT_TRUE(SameAnswers(CoreAnswers(ValidWorld({.seed = 7}), positions), response));
}

TEST_F(E2eNearestTest, ComparisonCatchesPlantedFaults) {
  const World world = ValidWorld({.seed = 7});
  const std::vector<Vec2> positions = TestPositions(5);
  const std::vector<NearestPoint> answers = CoreAnswers(world, positions);
  v1::NearestResponse response;
  ASSERT_TRUE(server_->Client().Nearest(RequestFor(world.spec(), positions), response).ok());
  ASSERT_TRUE(SameAnswers(answers, response));
  v1::NearestResponse fault = response;
  fault.set_f2(17, std::nextafter(fault.f2(17), 10.0));
  EXPECT_FALSE(SameAnswers(answers, fault));
  fault = response;
  fault.set_ids(3, fault.ids(3) ^ 1);
  EXPECT_FALSE(SameAnswers(answers, fault));
  fault = response;
  fault.mutable_cell_values()->RemoveLast();
  EXPECT_FALSE(SameAnswers(answers, fault));
}

TEST_F(E2eNearestTest, RefusesBadBatchesNamingTheField) {
  client::ScallopClient client = server_->Client();
  auto call = [&](const v1::NearestRequest& request) {
    v1::NearestResponse response;
    return client.Nearest(request, response);
  };
  v1::NearestRequest request = RequestFor(WorldSpec{.seed = 7}, {{0, 0}, {1, 1}});
  request.mutable_positions()->add_xs(2);
  grpc::Status status = call(request);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(status.error_message().rfind("positions:", 0), 0u) << status.error_message();

  status = call(RequestFor(WorldSpec{.seed = 7}, std::vector<Vec2>(kBatchLimit + 1)));
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(status.error_message().find("max_nearest_batch"), std::string::npos);
  EXPECT_TRUE(call(RequestFor(WorldSpec{.seed = 7}, std::vector<Vec2>(kBatchLimit))).ok());

  status = call(RequestFor(WorldSpec{.seed = 7}, {{0, 0}, {0, 0x1.0p32 + 1}}));
  EXPECT_EQ(status.error_code(), grpc::StatusCode::OUT_OF_RANGE);
  EXPECT_NE(status.error_message().find("positions[1].y"), std::string::npos);
  status = call(RequestFor(WorldSpec{.seed = 7}, {{NAN, 0}}));
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(status.error_message().find("positions[0].x"), std::string::npos);

  request = RequestFor(WorldSpec{.seed = 7}, {{0, 0}});
  request.set_world_name("atlantis");
  EXPECT_EQ(call(request).error_code(), grpc::StatusCode::NOT_FOUND);
  request = RequestFor(WorldSpec{.seed = 7, .min_distance = 0}, {{0, 0}});
  EXPECT_EQ(call(request).error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_TRUE(call(RequestFor(WorldSpec{.seed = 7}, {})).ok()) << "an empty batch is no error";
}

TEST_F(E2eNearestTest, NoiseGridIsTheCoresImage) {
  client::ScallopClient client = server_->Client();
  const World world = ValidWorld({.seed = 7});
  PlaneEngine engine({.threads = 1});
  NearestLookup lookup(engine);
  const std::pair<v1::NoiseChannel, NoiseChannel> channels[] = {
      {v1::NOISE_CHANNEL_F1, NoiseChannel::kF1},
      {v1::NOISE_CHANNEL_F2, NoiseChannel::kF2},
      {v1::NOISE_CHANNEL_F2_MINUS_F1, NoiseChannel::kF2MinusF1},
      {v1::NOISE_CHANNEL_ID, NoiseChannel::kId},
      {v1::NOISE_CHANNEL_CELL_VALUE, NoiseChannel::kCellValue}};
  for (const auto& [message_channel, channel] : channels) {
    v1::NoiseGridRequest request;
    request.set_world_name("coast");
    request.set_origin_x(-20.3);
    request.set_origin_y(5.7);
    request.set_step(0.31);
    request.set_width(120);
    request.set_height(90);
    request.set_channel(message_channel);
    v1::NoiseGridResponse response;
    const grpc::Status status = client.NoiseGrid(request, response);
    ASSERT_TRUE(status.ok()) << client::DescribeStatus(status);
    const NoiseGridSpec spec{
        .origin = {-20.3, 5.7}, .step = 0.31, .width = 120, .height = 90, .channel = channel};
    StatusOr<NoiseImage> image = EvaluateNoiseGrid(lookup, world, spec, kSampleLimit);
    ASSERT_TRUE(image.ok());
    EXPECT_EQ(response.width(), 120);
    EXPECT_EQ(response.height(), 90);
    ASSERT_EQ(static_cast<size_t>(response.values_size()), image->values.size());
    ASSERT_EQ(static_cast<size_t>(response.ids_size()), image->ids.size());
    int wrong = 0;
    for (size_t k = 0; k < image->values.size(); ++k) {
      wrong += !SameBits(response.values(static_cast<int>(k)), image->values[k]);
    }
    for (size_t k = 0; k < image->ids.size(); ++k) {
      wrong += response.ids(static_cast<int>(k)) != image->ids[k];
    }
    EXPECT_EQ(wrong, 0) << NoiseChannelName(channel);
  }
}

TEST_F(E2eNearestTest, RefusesBadGridsNamingTheField) {
  client::ScallopClient client = server_->Client();
  auto call = [&](int width, int height, double step, v1::NoiseChannel channel) {
    v1::NoiseGridRequest request;
    request.set_step(step);
    request.set_width(width);
    request.set_height(height);
    request.set_channel(channel);
    v1::NoiseGridResponse response;
    return client.NoiseGrid(request, response);
  };
  EXPECT_TRUE(call(100, 200, 0.5, v1::NOISE_CHANNEL_F1).ok());
  grpc::Status status = call(100, 201, 0.5, v1::NOISE_CHANNEL_F1);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(status.error_message().find("max_noise_grid_samples"), std::string::npos);
  status = call(10, 10, 0.5, v1::NOISE_CHANNEL_UNSPECIFIED);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(status.error_message().rfind("channel", 0), 0u);
  status = call(10, 10, -1, v1::NOISE_CHANNEL_F1);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(status.error_message().rfind("step", 0), 0u);
  status = call(10, 0, 1, v1::NOISE_CHANNEL_F1);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  status = call(10, 10, 1e9, v1::NOISE_CHANNEL_F1);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::OUT_OF_RANGE);
}

}  // namespace
}  // namespace scallop::testing
