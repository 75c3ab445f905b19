// End to end (issue 20, item 3): every answer the limits allow reaches a
// client with gRPC's default 4 MiB receive limit: each unary call at its
// limit, read through a plain channel; and a limit that would allow a larger
// answer is refused at start.
#include <gtest/gtest.h>

#include <fstream>

#include "scallop/random/rng.h"
#include "tests/e2e/scallopd_process.h"
#include "tests/test_worlds.h"
#include "world_messages.h"

namespace scallop::testing {
namespace {

// gRPC's default receive limit, which clients that never raised it have.
constexpr size_t kDefaultReceiveLimit = size_t{4} << 20;

class E2eMessageSizeTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // The largest page ValidateConfig allows; the other limits at their defaults,
    // which are their largest.
    server_ = ScallopdProcess::Start({"--max-page-size", "131072"}).release();
  }
  static void TearDownTestSuite() { delete server_; }
  void SetUp() override {
    ASSERT_NE(server_, nullptr);
    // A plain channel: nothing raised, nothing lowered.
    stub_ = v1::Scallop::NewStub(
        grpc::CreateChannel(server_->address(), grpc::InsecureChannelCredentials()));
    grpc::ClientContext context;
    v1::GetServerInfoRequest request;
    ASSERT_TRUE(stub_->GetServerInfo(&context, request, &info_).ok());
  }

  static ScallopdProcess* server_;
  std::unique_ptr<v1::Scallop::Stub> stub_;
  v1::GetServerInfoResponse info_;
};
ScallopdProcess* E2eMessageSizeTest::server_ = nullptr;

TEST_F(E2eMessageSizeTest, AFullPageFits) {
  ASSERT_EQ(info_.limits().max_page_size(), 131072);
  v1::GetPointsRequest request;
  *request.mutable_world() = WorldToMessage(ValidWorld({.seed = 41}));
  // About 150,000 points: more than a page.
  *request.mutable_rect() = RectToMessage({0, 0, 420, 420});
  grpc::ClientContext context;
  v1::GetPointsResponse response;
  const grpc::Status status = stub_->GetPoints(&context, request, &response);
  ASSERT_TRUE(status.ok()) << client::DescribeStatus(status);
  EXPECT_EQ(response.points().ids_size(), info_.limits().max_page_size());
  EXPECT_LE(response.ByteSizeLong(), kDefaultReceiveLimit);
}

TEST_F(E2eMessageSizeTest, AFullNearestBatchFits) {
  v1::NearestRequest request;
  *request.mutable_world() = WorldToMessage(ValidWorld({.seed = 42}));
  Rng rng(42);
  for (int k = 0; k < info_.limits().max_nearest_batch(); ++k) {
    request.mutable_positions()->add_xs(rng.Uniform(0, 64));
    request.mutable_positions()->add_ys(rng.Uniform(0, 64));
  }
  grpc::ClientContext context;
  v1::NearestResponse response;
  const grpc::Status status = stub_->Nearest(&context, request, &response);
  ASSERT_TRUE(status.ok()) << client::DescribeStatus(status);
  EXPECT_EQ(response.f1_size(), info_.limits().max_nearest_batch());
  EXPECT_LE(response.ByteSizeLong(), kDefaultReceiveLimit);
}

// Both kinds of answer: doubles in values, fixed64 in ids, 8 bytes a sample.
TEST_F(E2eMessageSizeTest, AFullNoiseGridFitsInEveryChannel) {
  const int64_t samples = info_.limits().max_noise_grid_samples();
  // The widest width up to 1,024 that divides the limit: an image of exactly
  // max_noise_grid_samples samples.
  int width = 1024;
  while (samples % width != 0) --width;
  for (v1::NoiseChannel channel : {v1::NOISE_CHANNEL_F1, v1::NOISE_CHANNEL_ID}) {
    v1::NoiseGridRequest request;
    *request.mutable_world() = WorldToMessage(ValidWorld({.seed = 43}));
    request.set_step(0.05);
    request.set_width(width);
    request.set_height(static_cast<int>(samples / width));
    request.set_channel(channel);
    grpc::ClientContext context;
    v1::NoiseGridResponse response;
    const grpc::Status status = stub_->NoiseGrid(&context, request, &response);
    ASSERT_TRUE(status.ok()) << client::DescribeStatus(status) << " " << samples << " samples";
    EXPECT_EQ(response.values_size() + response.ids_size(), samples);
    EXPECT_LE(response.ByteSizeLong(), kDefaultReceiveLimit);
  }
}

TEST(E2eMessageSizeLimitTest, ALimitAllowingALargerAnswerIsRefused) {
  auto server = ScallopdProcess::Start({"--max-page-size", "131073"});
  EXPECT_TRUE(server == nullptr);
  const std::string config = ::testing::TempDir() + "e2e_message_size.yaml";
  std::ofstream(config) << "max_noise_grid_samples: 500001\n";
  server = ScallopdProcess::Start({"--config", config});
  EXPECT_TRUE(server == nullptr);
  std::remove(config.c_str());
}

}  // namespace
}  // namespace scallop::testing
