// End to end: deadlines and cancellation stop a stream mid-way and the server
// goes on serving; SIGTERM turns health NOT_SERVING, lets in-flight calls
// finish within the grace period, and exits 0.
#include <gtest/gtest.h>
#include <signal.h>

#include <atomic>
#include <thread>

#include "grpc/health/v1/health.grpc.pb.h"
#include "scallop/plane/plane_engine.h"
#include "tests/e2e/scallopd_process.h"
#include "tests/test_worlds.h"
#include "world_messages.h"

namespace scallop::testing {
namespace {

using std::chrono::milliseconds;

v1::StreamPointsRequest StreamRequest(const Rect& rect) {
  v1::StreamPointsRequest request;
  *request.mutable_world() = WorldToMessage(ValidWorld({.seed = 21}));
  *request.mutable_rect() = RectToMessage(rect);
  return request;
}

// Big enough that no test run streams it to the end: 62,500 regions.
const Rect kHugeRect{0, 0, 4000, 4000};

void ExpectStillServing(client::ScallopClient& client) {
  v1::GetPointsRequest request;
  *request.mutable_rect() = RectToMessage({0, 0, 10, 10});
  v1::GetPointsResponse response;
  const grpc::Status status = client.GetPoints(request, response);
  EXPECT_TRUE(status.ok()) << client::DescribeStatus(status);
}

TEST(E2eLifecycleTest, DeadlineStopsAStreamMidway) {
  auto server = ScallopdProcess::Start({});
  ASSERT_NE(server, nullptr);
  client::ScallopClient client = server->Client();
  int chunks = 0;
  // The deadline, not the end of the rectangle, ends the stream: kHugeRect
  // takes tens of seconds to stream, and the server logs the call cancelled.
  const grpc::Status status = client.StreamPoints(
      StreamRequest(kHugeRect), [&](const v1::PointsChunk&) { return ++chunks > 0; },
      {.timeout = milliseconds(500)});
  EXPECT_EQ(status.error_code(), grpc::StatusCode::DEADLINE_EXCEEDED);
  EXPECT_GT(chunks, 0);
  ExpectStillServing(client);
  // The server noticed, stopped the stream and logged it.
  std::string log;
  for (int attempt = 0; attempt < 750; ++attempt) {
    log = server->Log();
    if (log.find("StreamPoints") != std::string::npos) break;
    std::this_thread::sleep_for(milliseconds(20));
  }
  EXPECT_NE(log.find("code=CANCELLED"), std::string::npos) << log;
}

TEST(E2eLifecycleTest, CancellationStopsAStreamMidway) {
  auto server = ScallopdProcess::Start({});
  ASSERT_NE(server, nullptr);
  client::ScallopClient client = server->Client();
  int chunks = 0;
  const grpc::Status status = client.StreamPoints(
      StreamRequest(kHugeRect), [&](const v1::PointsChunk&) { return ++chunks < 5; });
  EXPECT_EQ(status.error_code(), grpc::StatusCode::CANCELLED);
  EXPECT_EQ(chunks, 5);
  ExpectStillServing(client);
  std::string log;
  for (int attempt = 0; attempt < 750; ++attempt) {
    log = server->Log();
    if (log.find("StreamPoints") != std::string::npos) break;
    std::this_thread::sleep_for(milliseconds(20));
  }
  EXPECT_NE(log.find("StreamPoints"), std::string::npos);
  EXPECT_NE(log.find("code=CANCELLED"), std::string::npos) << log;
}

TEST(E2eLifecycleTest, SigtermGoesNotServingAndFinishesInFlightCallsThenExitsZero) {
  auto server = ScallopdProcess::Start({"--drain-seconds", "1", "--grace-seconds", "60"});
  ASSERT_NE(server, nullptr);
  client::ScallopClient client = server->Client();
  // 2,500 regions, about 550k points in some 2,500 chunks, read at most one
  // a millisecond: the stream outlasts the 1 s drain however fast the machine,
  // so it is still in flight when Shutdown begins.
  const Rect rect{-400, -400, 400, 400};
  PlanePoints streamed;
  std::atomic<int> chunks{0};
  grpc::Status stream_status;
  std::thread reader([&] {
    stream_status = client.StreamPoints(StreamRequest(rect), [&](const v1::PointsChunk& chunk) {
      ++chunks;
      std::this_thread::sleep_for(milliseconds(1));
      return ReadPoints(chunk.points(), streamed).ok();
    });
  });
  while (chunks < 3) std::this_thread::sleep_for(milliseconds(1));
  server->Signal(SIGTERM);
  // From the signal on, the health check answers NOT_SERVING: through the
  // drain and while the stream finishes.
  bool saw_not_serving = false;
  for (int attempt = 0; attempt < 200 && !saw_not_serving; ++attempt) {
    grpc::ClientContext context;
    grpc::health::v1::HealthCheckResponse health;
    const grpc::Status status =
        grpc::health::v1::Health::NewStub(client.channel())->Check(&context, {}, &health);
    saw_not_serving =
        status.ok() && health.status() == grpc::health::v1::HealthCheckResponse::NOT_SERVING;
    std::this_thread::sleep_for(milliseconds(10));
  }
  EXPECT_TRUE(saw_not_serving);
  reader.join();
  ASSERT_TRUE(stream_status.ok()) << client::DescribeStatus(stream_status);
  EXPECT_EQ(server->WaitForExit(milliseconds(30000)), 0);
  // The stream was in flight at the signal, and it was delivered whole.
  const std::string log = server->Log();
  ASSERT_NE(log.find("signal 15"), std::string::npos) << log;
  ASSERT_NE(log.find("StreamPoints"), std::string::npos) << log;
  EXPECT_LT(log.find("signal 15"), log.find("StreamPoints")) << log;
  PlaneEngine engine({.threads = 2});
  StatusOr<PlanePoints> core = engine.Points(ValidWorld({.seed = 21}), rect);
  ASSERT_TRUE(core.ok());
  EXPECT_EQ(core->ids, streamed.ids);
}

TEST(E2eLifecycleTest, AStalledReaderHoldsTheServerBack) {
  auto server = ScallopdProcess::Start({});
  ASSERT_NE(server, nullptr);
  client::ScallopClient client = server->Client();
  // Read one chunk, stall for 3 s, cancel. Unthrottled, the server would
  // generate over a million points in that time (about 480k a second cold on
  // this machine); with writes paced by OnWriteDone it stops once gRPC's flow
  // control window (a few MB, some 100k points) is full. gRPC 1.51 reports
  // the cancel to a server blocked on a write only when that write completes,
  // about 2 s later here, hence the patient wait for the log line.
  const grpc::Status status =
      client.StreamPoints(StreamRequest(kHugeRect), [&](const v1::PointsChunk&) {
        std::this_thread::sleep_for(milliseconds(3000));
        return false;
      });
  EXPECT_EQ(status.error_code(), grpc::StatusCode::CANCELLED);
  std::string log;
  for (int attempt = 0; attempt < 750; ++attempt) {
    log = server->Log();
    if (log.find("StreamPoints") != std::string::npos) break;
    std::this_thread::sleep_for(milliseconds(20));
  }
  const size_t at = log.find("points=", log.find("StreamPoints"));
  ASSERT_NE(at, std::string::npos) << log;
  const long long points_sent = std::stoll(log.substr(at + 7));
  EXPECT_LT(points_sent, 500000) << log;
  ExpectStillServing(client);
}

TEST(E2eLifecycleTest, CallsOutlivingTheGracePeriodAreCutAndTheServerStillExitsZero) {
  auto server = ScallopdProcess::Start({"--grace-seconds", "0.5"});
  ASSERT_NE(server, nullptr);
  client::ScallopClient client = server->Client();
  std::atomic<int> chunks{0};
  grpc::Status stream_status;
  std::thread reader([&] {
    stream_status = client.StreamPoints(StreamRequest(kHugeRect), [&](const v1::PointsChunk&) {
      ++chunks;
      std::this_thread::sleep_for(milliseconds(5));
      return true;
    });
  });
  while (chunks < 3) std::this_thread::sleep_for(milliseconds(5));
  server->Signal(SIGTERM);
  // The stream has minutes left (62,500 chunks read at most one each 5 ms),
  // so an exit within 15 s means the grace period cut it.
  EXPECT_EQ(server->WaitForExit(milliseconds(15000)), 0);
  reader.join();
  EXPECT_FALSE(stream_status.ok());
}

// Issue 20: gRPC shares ports by default (SO_REUSEPORT), so a second server
// on a port in use started silently and took half the connections. It must
// refuse, unless both ask to share.
TEST(E2eLifecycleTest, ASecondServerOnAPortInUseRefusesUnlessAskedToShare) {
  auto first = ScallopdProcess::Start({});
  ASSERT_NE(first, nullptr);
  auto second = ScallopdProcess::Start({}, first->address());
  EXPECT_TRUE(second == nullptr) << "started on " << first->address() << ", already in use";

  auto sharing = ScallopdProcess::Start({"--reuse-port"});
  ASSERT_NE(sharing, nullptr);
  auto sharing_too = ScallopdProcess::Start({"--reuse-port"}, sharing->address());
  EXPECT_NE(sharing_too, nullptr);
}

}  // namespace
}  // namespace scallop::testing
