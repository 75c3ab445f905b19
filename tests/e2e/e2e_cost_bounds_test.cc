// End to end (issue 20, item 1): Nearest and NoiseGrid are bounded by the
// distinct regions they touch, checked before any work, and an abandoned call
// (deadline, cancellation, SIGTERM) stops its work, so it frees the server.
#include <gtest/gtest.h>
#include <signal.h>

#include <fstream>
#include <sstream>
#include <thread>

#include "tests/e2e/metrics_scrape.h"
#include "tests/e2e/scallopd_process.h"
#include "tests/test_worlds.h"
#include "world_messages.h"

namespace scallop::testing {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

constexpr int64_t kRegionLimit = 64;

// One position in each of `count` regions three regions apart, so that every
// search grid needs its own cold generation: the scattered worst case.
v1::NearestRequest ScatteredNearest(uint64_t seed, int count) {
  v1::NearestRequest request;
  *request.mutable_world() = WorldToMessage(ValidWorld({.seed = seed}));
  for (int k = 0; k < count; ++k) {
    request.mutable_positions()->add_xs(48.0 * (k % 64) + 8.5);
    request.mutable_positions()->add_ys(48.0 * (k / 64) + 8.5);
  }
  return request;
}

// A width x height image with one sample in each of width * height regions
// three apart (step 48 d), likewise cold everywhere.
v1::NoiseGridRequest ScatteredNoiseGrid(uint64_t seed, int width, int height) {
  v1::NoiseGridRequest request;
  *request.mutable_world() = WorldToMessage(ValidWorld({.seed = seed}));
  request.set_origin_x(-5000.5);
  request.set_origin_y(-5000.5);
  request.set_step(48);
  request.set_width(width);
  request.set_height(height);
  request.set_channel(v1::NOISE_CHANNEL_F1);
  return request;
}

// Whether a log line of `method` says code=OK: its work ran to the end.
bool AnsweredInLog(const std::string& log, const std::string& method) {
  std::istringstream lines(log);
  for (std::string line; std::getline(lines, line);) {
    if (line.find("] " + method + " ") != std::string::npos &&
        line.find("code=OK") != std::string::npos) {
      return true;
    }
  }
  return false;
}

TEST(E2eCostBoundsTest, RegionLimitIsReportedAndCheckedBeforeWork) {
  const std::string config = ::testing::TempDir() + "e2e_cost_bounds.yaml";
  std::ofstream(config) << "max_nearest_regions: " << kRegionLimit << "\n";
  auto server = ScallopdProcess::Start({"--config", config});
  ASSERT_NE(server, nullptr);
  client::ScallopClient client = server->Client();
  v1::GetServerInfoResponse info;
  ASSERT_TRUE(client.GetServerInfo(info).ok());
  EXPECT_EQ(info.limits().max_nearest_regions(), kRegionLimit);

  // At the limit: answered. Many positions in few regions cost little.
  v1::NearestRequest within = ScatteredNearest(3, kRegionLimit);
  for (int k = 0; k < 3000; ++k) {
    within.mutable_positions()->add_xs(8.5 + 0.002 * k);
    within.mutable_positions()->add_ys(8.5);
  }
  v1::NearestResponse answer;
  grpc::Status status = client.Nearest(within, answer);
  EXPECT_TRUE(status.ok()) << client::DescribeStatus(status);
  // One region more: refused, naming the field and the setting.
  status = client.Nearest(ScatteredNearest(3, kRegionLimit + 1), answer);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(status.error_message().find("positions"), std::string::npos) << status.error_message();
  EXPECT_NE(status.error_message().find("max_nearest_regions"), std::string::npos);

  v1::NoiseGridResponse image;
  status = client.NoiseGrid(ScatteredNoiseGrid(3, 8, 8), image);
  EXPECT_TRUE(status.ok()) << client::DescribeStatus(status);
  status = client.NoiseGrid(ScatteredNoiseGrid(3, kRegionLimit + 1, 1), image);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(status.error_message().find("step"), std::string::npos) << status.error_message();
  EXPECT_NE(status.error_message().find("max_nearest_regions"), std::string::npos);
  std::remove(config.c_str());
}

// One request thread: an abandoned call still working would hold it. The
// abandoned calls are seconds of cold grids each (4,096 regions, the
// default limit); the later call is cold too, so it needs that thread.
TEST(E2eCostBoundsTest, AbandonedCallsStopAndFreeTheServer) {
  auto server = ScallopdProcess::Start({"--threads", "1"});
  ASSERT_NE(server, nullptr);
  client::ScallopClient client = server->Client();
  v1::NearestResponse answer;
  const grpc::Status expired =
      client.Nearest(ScatteredNearest(11, 4096), answer, {.timeout = milliseconds(300)});
  EXPECT_EQ(expired.error_code(), grpc::StatusCode::DEADLINE_EXCEEDED);

  // Cancelled (not expired) while the server works on it.
  auto stub = v1::Scallop::NewStub(
      grpc::CreateChannel(server->address(), grpc::InsecureChannelCredentials()));
  grpc::ClientContext context;
  v1::NoiseGridResponse image;
  grpc::Status cancelled;
  std::thread caller(
      [&] { cancelled = stub->NoiseGrid(&context, ScatteredNoiseGrid(12, 64, 64), &image); });
  std::this_thread::sleep_for(milliseconds(300));
  context.TryCancel();
  caller.join();
  EXPECT_EQ(cancelled.error_code(), grpc::StatusCode::CANCELLED);

  // A cold call is answered at once: it had waited seconds behind the
  // abandoned work (6.7 s in all for the Nearest alone, on one thread).
  v1::GetPointsRequest request;
  *request.mutable_world() = WorldToMessage(ValidWorld({.seed = 13}));
  *request.mutable_rect() = RectToMessage({0, 0, 20, 20});
  v1::GetPointsResponse points;
  const grpc::Status status = client.GetPoints(request, points, {.timeout = seconds(3)});
  EXPECT_TRUE(status.ok()) << client::DescribeStatus(status);
  // The server logged both as ended, neither as answered.
  const std::string log = server->WaitForLog("] NoiseGrid ", seconds(60));
  EXPECT_NE(log.find("] Nearest "), std::string::npos) << log;
  EXPECT_FALSE(AnsweredInLog(log, "Nearest")) << log;
  EXPECT_FALSE(AnsweredInLog(log, "NoiseGrid")) << log;
}

// The calls that generate rectangles stop too: a cold GetPoints and a cold
// Verify of the largest area (about 3,900 regions, some 600 ms of generation
// on one thread here) expire within 100 ms; the server logs them as
// stopped, where the old one generated (and verified) to the end, code=OK.
TEST(E2eCostBoundsTest, ExpiredColdRectanglesStopGenerating) {
  auto server = ScallopdProcess::Start({"--threads", "1"});
  ASSERT_NE(server, nullptr);
  client::ScallopClient client = server->Client();
  v1::GetPointsRequest big;
  *big.mutable_world() = WorldToMessage(ValidWorld({.seed = 21}));
  *big.mutable_rect() = RectToMessage({0, 0, 1000, 1000});
  v1::GetPointsResponse points;
  EXPECT_EQ(client.GetPoints(big, points, {.timeout = milliseconds(100)}).error_code(),
            grpc::StatusCode::DEADLINE_EXCEEDED);
  std::string log = server->WaitForLog("] GetPoints ", seconds(60));
  EXPECT_FALSE(AnsweredInLog(log, "GetPoints")) << log;

  v1::VerifyRequest verify;
  *verify.mutable_world() = WorldToMessage(ValidWorld({.seed = 22}));
  // The largest Verify allows: grown by its 2 d halo, 1000 d x 1000 d.
  *verify.mutable_rect() = RectToMessage({2, 2, 998, 998});
  v1::VerifyResponse report;
  EXPECT_EQ(client.Verify(verify, report, {.timeout = milliseconds(100)}).error_code(),
            grpc::StatusCode::DEADLINE_EXCEEDED);
  log = server->WaitForLog("] Verify ", seconds(60));
  EXPECT_FALSE(AnsweredInLog(log, "Verify")) << log;
}

// A warm Verify has nothing left to generate: its time is the Delaunay check
// (about 2 s for 1500 d x 1500 d, 1.9M points, against a 600 ms deadline),
// which now polls the deadline too. The old server checked to the end and
// logged code=OK.
TEST(E2eCostBoundsTest, AnExpiredWarmVerifyStopsInTheVerifier) {
  auto server = ScallopdProcess::Start(
      {"--threads", "1", "--max-query-area", "2.3e6", "--max-verify-area", "2.3e6"});
  ASSERT_NE(server, nullptr);
  client::ScallopClient client = server->Client();
  v1::GetPointsRequest warm;
  *warm.mutable_world() = WorldToMessage(ValidWorld({.seed = 23}));
  *warm.mutable_rect() = RectToMessage({0, 0, 1500, 1500});
  warm.set_page_size(1);
  v1::GetPointsResponse points;
  const grpc::Status warmed = client.GetPoints(warm, points, {.timeout = seconds(120)});
  ASSERT_TRUE(warmed.ok()) << client::DescribeStatus(warmed);
  v1::VerifyRequest verify;
  *verify.mutable_world() = WorldToMessage(ValidWorld({.seed = 23}));
  *verify.mutable_rect() = RectToMessage({2, 2, 1498, 1498});
  v1::VerifyResponse report;
  EXPECT_EQ(client.Verify(verify, report, {.timeout = milliseconds(600)}).error_code(),
            grpc::StatusCode::DEADLINE_EXCEEDED);
  const std::string log = server->WaitForLog("] Verify ", seconds(60));
  EXPECT_FALSE(AnsweredInLog(log, "Verify")) << log;
  EXPECT_NE(log.find("verify: stopped before the end"), std::string::npos) << log;
}

TEST(E2eCostBoundsTest, SigtermDuringABigCallExitsWithinTheGrace) {
  auto server = ScallopdProcess::Start(
      {"--threads", "1", "--grace-seconds", "1", "--metrics-listen", "127.0.0.1:0"});
  ASSERT_NE(server, nullptr);
  const std::string line = server->ReadStdoutLine(seconds(10));
  const std::string metrics_address = line.substr(line.rfind(' ') + 1);
  client::ScallopClient client = server->Client();
  std::thread caller([&] {
    v1::NearestResponse answer;
    client.Nearest(ScatteredNearest(17, 4096), answer);
  });
  // The event: the call is admitted and running.
  const auto deadline = std::chrono::steady_clock::now() + seconds(20);
  while (ScrapeMetrics(metrics_address)["scallop_requests_in_flight"] < 1 &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(milliseconds(10));
  }
  server->Signal(SIGTERM);
  // Grace 1 s, then the call is cancelled and must stop: well within 4 s,
  // where the whole call (never stopping) took about 7 s.
  EXPECT_EQ(server->WaitForExit(seconds(4)), 0) << server->Log();
  caller.join();
}

}  // namespace
}  // namespace scallop::testing
