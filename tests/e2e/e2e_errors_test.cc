// End to end: every bad input gets its status code and a message naming the
// field, and the server keeps serving afterwards (contract item 7).
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <thread>

#include "follow_client.h"
#include "tests/e2e/scallopd_process.h"
#include "tests/test_worlds.h"
#include "world_messages.h"

namespace scallop::testing {
namespace {

struct BadRequest {
  const char* name;
  v1::GetPointsRequest request;
  grpc::StatusCode code;
  const char* message_part;  // the field the message must name
};

v1::GetPointsRequest Request(const WorldSpec& world, const Rect& rect) {
  v1::GetPointsRequest request;
  *request.mutable_world() = WorldToMessage(world);
  *request.mutable_rect() = RectToMessage(rect);
  return request;
}

std::vector<BadRequest> BadRequests() {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const WorldSpec good{.seed = 5};
  const Rect square{0, 0, 10, 10};
  std::vector<BadRequest> cases;
  auto add = [&](const char* name, v1::GetPointsRequest request, grpc::StatusCode code,
                 const char* part) {
    cases.push_back({name, std::move(request), code, part});
  };
  using enum grpc::StatusCode;
  add("nan corner", Request(good, {nan, 0, 10, 10}), INVALID_ARGUMENT, "rect.x0");
  add("infinite corner", Request(good, {0, 0, 10, inf}), INVALID_ARGUMENT, "rect.y1");
  add("negative infinite corner", Request(good, {0, -inf, 10, 10}), INVALID_ARGUMENT, "rect.y0");
  add("inverted x", Request(good, {10, 0, 0, 10}), INVALID_ARGUMENT, "x0 must be less than x1");
  add("inverted y", Request(good, {0, 10, 10, 0}), INVALID_ARGUMENT, "y0 must be less than y1");
  add("empty", Request(good, {3, 0, 3, 10}), INVALID_ARGUMENT, "x0 must be less than x1");
  v1::GetPointsRequest no_rect;
  *no_rect.mutable_world() = WorldToMessage(good);
  add("missing rect", no_rect, INVALID_ARGUMENT, "rect: required");
  add("zero d", Request(WorldSpec{.min_distance = 0}, square), INVALID_ARGUMENT,
      "world.min_distance");
  add("negative d", Request(WorldSpec{.min_distance = -1}, square), INVALID_ARGUMENT,
      "world.min_distance");
  add("nan d", Request(WorldSpec{.min_distance = nan}, square), INVALID_ARGUMENT,
      "world.min_distance");
  add("density above 2",
      Request(WorldSpec{.algorithm = WorldAlgorithm::kA1, .density = 2.5}, square),
      INVALID_ARGUMENT, "world.density");
  add("density at 1", Request(WorldSpec{.algorithm = WorldAlgorithm::kA2, .density = 1.0}, square),
      INVALID_ARGUMENT, "world.density");
  auto unspecified = Request(good, square);
  unspecified.mutable_world()->set_algorithm(v1::ALGORITHM_UNSPECIFIED);
  add("unspecified algorithm", unspecified, INVALID_ARGUMENT, "world.algorithm");
  auto old_version = Request(good, square);
  old_version.mutable_world()->set_generator_version(kGeneratorVersion + 1);
  add("unknown generator version", old_version, INVALID_ARGUMENT, "world.generator_version");
  auto unknown = Request(good, square);
  unknown.set_world_name("atlantis");
  add("unknown world name", unknown, NOT_FOUND, "world_name");
  add("area over the limit", Request(good, {0, 0, 2000, 2000}), INVALID_ARGUMENT, "max_query_area");
  add("thin rectangle crossing too many regions", Request(good, {0, 0, 1e9, 1e-6}),
      INVALID_ARGUMENT, "regions");
  add("beyond the precision range", Request(good, {0x1.0p33, 0, 0x1.0p33 + 10, 10}), OUT_OF_RANGE,
      "rect.x0");
  add("beyond the precision range, small d",
      Request(WorldSpec{.min_distance = 1e-3}, {0, 5e6, 10, 5e6 + 1}), OUT_OF_RANGE, "rect.y0");
  auto negative_page = Request(good, square);
  negative_page.set_page_size(-1);
  add("negative page size", negative_page, INVALID_ARGUMENT, "page_size");
  auto garbage_token = Request(good, square);
  garbage_token.set_page_token("not-a-token");
  add("garbage page token", garbage_token, INVALID_ARGUMENT, "page_token");
  return cases;
}

class E2eErrorsTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { server_ = ScallopdProcess::Start({}).release(); }
  static void TearDownTestSuite() { delete server_; }
  void SetUp() override { ASSERT_NE(server_, nullptr); }

  // A good request still works: the server kept serving.
  static void ExpectStillServing() {
    v1::GetPointsResponse response;
    grpc::Status status =
        server_->Client().GetPoints(Request(WorldSpec{.seed = 5}, {0, 0, 20, 20}), response);
    ASSERT_TRUE(status.ok()) << client::DescribeStatus(status);
    EXPECT_GT(response.points().ids_size(), 100);
  }

  static ScallopdProcess* server_;
};
ScallopdProcess* E2eErrorsTest::server_ = nullptr;

TEST_F(E2eErrorsTest, EveryBadInputGetsItsCodeAndNamesTheField) {
  client::ScallopClient client = server_->Client();
  for (const BadRequest& bad : BadRequests()) {
    SCOPED_TRACE(bad.name);
    v1::GetPointsResponse response;
    const grpc::Status status = client.GetPoints(bad.request, response);
    EXPECT_EQ(status.error_code(), bad.code) << client::DescribeStatus(status);
    EXPECT_NE(status.error_message().find(bad.message_part), std::string::npos)
        << client::DescribeStatus(status);
    // The same input through the stream and Verify gets the same code.
    v1::StreamPointsRequest stream;
    if (bad.request.has_world()) *stream.mutable_world() = bad.request.world();
    if (!bad.request.world_name().empty()) stream.set_world_name(bad.request.world_name());
    if (bad.request.has_rect()) *stream.mutable_rect() = bad.request.rect();
    const bool paging_only = bad.request.page_size() < 0 || !bad.request.page_token().empty();
    const bool area_only = std::string(bad.message_part) == "max_query_area";
    if (!paging_only && !area_only) {
      const grpc::Status streamed = client.StreamPoints(stream, [](const auto&) { return true; });
      EXPECT_EQ(streamed.error_code(), bad.code) << client::DescribeStatus(streamed);
    }
    ExpectStillServing();
  }
  // One log line per request, with the code.
  EXPECT_NE(server_->Log().find("code=OUT_OF_RANGE"), std::string::npos);
  EXPECT_NE(server_->Log().find("code=NOT_FOUND"), std::string::npos);
}

TEST_F(E2eErrorsTest, TamperedOrForeignPageTokensAreRejected) {
  client::ScallopClient client = server_->Client();
  auto request = Request(WorldSpec{.seed = 5}, {0, 0, 40, 40});
  request.set_page_size(100);
  v1::GetPointsResponse first;
  ASSERT_TRUE(client.GetPoints(request, first).ok());
  const std::string token = first.next_page_token();
  ASSERT_FALSE(token.empty());
  // Every single-character edit is caught (hex digits: flip one to another).
  for (size_t k = 0; k < token.size(); ++k) {
    std::string tampered = token;
    tampered[k] = tampered[k] == '0' ? '1' : '0';
    request.set_page_token(tampered);
    v1::GetPointsResponse response;
    const grpc::Status status = client.GetPoints(request, response);
    ASSERT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << "edit at " << k;
    ASSERT_NE(status.error_message().find("page_token"), std::string::npos);
  }
  request.set_page_token(token.substr(0, token.size() - 2));
  v1::GetPointsResponse response;
  EXPECT_EQ(client.GetPoints(request, response).error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  // A valid token for another rectangle or world.
  request.set_page_token(token);
  *request.mutable_rect() = RectToMessage({0, 0, 40, 41});
  grpc::Status status = client.GetPoints(request, response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(status.error_message().find("another world or rect"), std::string::npos);
  *request.mutable_rect() = RectToMessage({0, 0, 40, 40});
  request.mutable_world()->set_seed(6);
  EXPECT_EQ(client.GetPoints(request, response).error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  request.mutable_world()->set_seed(5);
  ASSERT_TRUE(client.GetPoints(request, response).ok());
  ExpectStillServing();
}

TEST_F(E2eErrorsTest, VerifyLimitsItsAreaAndReportsAPass) {
  client::ScallopClient client = server_->Client();
  v1::VerifyRequest request;
  *request.mutable_world() =
      WorldToMessage(ValidWorld({.seed = 9, .algorithm = WorldAlgorithm::kA2}));
  *request.mutable_rect() = RectToMessage({-30, -30, 30, 30});
  v1::VerifyResponse report;
  const grpc::Status status = client.Verify(request, report);
  ASSERT_TRUE(status.ok()) << client::DescribeStatus(status);
  EXPECT_TRUE(report.passed());
  EXPECT_TRUE(report.spacing_ok());
  EXPECT_TRUE(report.maximal_ok());
  EXPECT_GT(report.points_checked(), 2000);
  EXPECT_GT(report.pairs_across_seams(), 0);
  EXPECT_GE(report.min_distance(), 1.0);
  EXPECT_LT(report.largest_empty_circle(), 1.0 + 1e-6);
  *request.mutable_rect() = RectToMessage({0, 0, 1001, 1000});
  const grpc::Status too_big = client.Verify(request, report);
  EXPECT_EQ(too_big.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(too_big.error_message().find("max_verify_area"), std::string::npos);
  ExpectStillServing();
}

TEST(E2eLoadSheddingTest, StreamsBeyondMaxStreamsInFlightGetResourceExhausted) {
  auto server = ScallopdProcess::Start(
      {"--max-in-flight", "1", "--max-streams-in-flight", "1", "--threads", "1"});
  ASSERT_NE(server, nullptr);
  client::ScallopClient client = server->Client();
  // Hold the only stream slot with a slow stream read one chunk at a time.
  v1::StreamPointsRequest slow;
  *slow.mutable_world() = WorldToMessage(ValidWorld({.seed = 2}));
  *slow.mutable_rect() = RectToMessage({0, 0, 4000, 4000});
  std::atomic<bool> holding{false}, release{false};
  std::thread holder([&] {
    client.StreamPoints(slow, [&](const v1::PointsChunk&) {
      holding = true;
      return !release.load();
    });
  });
  while (!holding) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  // Streams and unary calls have their own slots: the stream takes none of
  // the unary one.
  v1::GetPointsResponse response;
  const grpc::Status unary = client.GetPoints(Request(WorldSpec{}, {0, 0, 5, 5}), response);
  EXPECT_TRUE(unary.ok()) << client::DescribeStatus(unary);
  // Other streams are shed, and give back no slot they never had.
  v1::StreamPointsRequest second = slow;
  *second.mutable_rect() = RectToMessage({0, 0, 5, 5});
  int chunks = 0;
  const grpc::Status shed_stream = client.StreamPoints(second, [&](const v1::PointsChunk&) {
    ++chunks;
    return true;
  });
  EXPECT_EQ(shed_stream.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(shed_stream.error_message().find("max_streams_in_flight"), std::string::npos);
  EXPECT_EQ(chunks, 0);
  {
    client::FollowSession follow(client);
    v1::FollowRequest update;
    *update.mutable_world() = WorldToMessage(ValidWorld({.seed = 2}));
    *update.mutable_viewport() = RectToMessage({0, 0, 5, 5});
    const grpc::Status shed_follow = follow.Update(update, [](const v1::FollowResponse&) {});
    EXPECT_EQ(shed_follow.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
    EXPECT_NE(shed_follow.error_message().find("max_streams_in_flight"), std::string::npos);
  }
  release = true;
  holder.join();
  // The slot is free again once the stream has ended.
  grpc::Status status;
  for (int attempt = 0; attempt < 100; ++attempt) {
    chunks = 0;
    status = client.StreamPoints(second, [&](const v1::PointsChunk&) { return true; });
    if (status.ok()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_TRUE(status.ok()) << client::DescribeStatus(status);
}

TEST(E2eLoadSheddingTest, UnaryCallsBeyondMaxInFlightGetResourceExhausted) {
  auto server = ScallopdProcess::Start({"--max-in-flight", "1", "--threads", "1"});
  ASSERT_NE(server, nullptr);
  client::ScallopClient client = server->Client();
  // A cold Verify of nearly the largest area holds the only unary slot for
  // seconds on one thread; the event waited for is a refusal while it runs.
  // 990 d, not 1000: grown by its 2 d halo, 1000 d is over max_verify_area
  // and was refused at once, so the test passed only when a GetPoints
  // happened to arrive in that instant.
  v1::VerifyRequest slow;
  *slow.mutable_world() = WorldToMessage(ValidWorld({.seed = 3}));
  *slow.mutable_rect() = RectToMessage({0, 0, 990, 990});
  std::atomic<bool> verified{false};
  grpc::Status verify_status;
  std::thread holder([&] {
    v1::VerifyResponse report;
    // Retried while our own GetPoints holds the slot at the moment it arrives.
    do {
      verify_status = client.Verify(slow, report);
    } while (verify_status.error_code() == grpc::StatusCode::RESOURCE_EXHAUSTED);
    verified = true;
  });
  grpc::Status shed;
  v1::GetPointsResponse response;
  while (!verified && shed.ok()) {
    shed = client.GetPoints(Request(WorldSpec{}, {0, 0, 5, 5}), response);
  }
  holder.join();
  EXPECT_TRUE(verify_status.ok()) << client::DescribeStatus(verify_status);
  EXPECT_EQ(shed.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED)
      << "the Verify ended before any call was refused";
  EXPECT_NE(shed.error_message().find("max_in_flight"), std::string::npos);
  const grpc::Status after = client.GetPoints(Request(WorldSpec{}, {0, 0, 5, 5}), response);
  EXPECT_TRUE(after.ok()) << client::DescribeStatus(after);
}

}  // namespace
}  // namespace scallop::testing
