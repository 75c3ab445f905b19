// End to end (issue 20, item 2): streams that stop reading or sending give
// their slots back (stream_stall_seconds, follow_idle_seconds), and streams
// and unary calls are admitted from separate budgets, so neither starves the
// other.
#include <gtest/gtest.h>

#include <fstream>
#include <memory>
#include <thread>
#include <vector>

#include "follow_client.h"
#include "tests/e2e/metrics_scrape.h"
#include "tests/e2e/scallopd_process.h"
#include "tests/test_worlds.h"
#include "world_messages.h"

namespace scallop::testing {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

v1::StreamPointsRequest StreamRequest(const Rect& rect) {
  v1::StreamPointsRequest request;
  *request.mutable_world() = WorldToMessage(ValidWorld({.seed = 31}));
  *request.mutable_rect() = RectToMessage(rect);
  return request;
}

grpc::Status SmallGetPoints(client::ScallopClient& client) {
  v1::GetPointsRequest request;
  *request.mutable_rect() = RectToMessage({0, 0, 10, 10});
  v1::GetPointsResponse response;
  return client.GetPoints(request, response, {.timeout = seconds(10)});
}

// A StreamPoints call whose client never reads: the server's writes fill the
// transport's window and then wait.
struct UnreadStream {
  grpc::ClientContext context;
  std::unique_ptr<grpc::ClientReader<v1::PointsChunk>> reader;
};

// 64 unread streams at the defaults (as many as max_in_flight's default):
// on the old server they took every slot, and every other call was
// RESOURCE_EXHAUSTED for as long as they stayed.
TEST(E2eStreamSlotsTest, UnreadStreamsNeitherStarveUnaryCallsNorStayForEver) {
  auto server = ScallopdProcess::Start({"--metrics-listen", "127.0.0.1:0"});
  ASSERT_NE(server, nullptr);
  const std::string metrics = server->ReadAnnouncedAddress("scallopd metrics on ");
  ASSERT_FALSE(metrics.empty());
  client::ScallopClient client = server->Client();
  auto stub = v1::Scallop::NewStub(
      grpc::CreateChannel(server->address(), grpc::InsecureChannelCredentials()));
  std::vector<std::unique_ptr<UnreadStream>> streams;
  for (int k = 0; k < 64; ++k) {
    streams.push_back(std::make_unique<UnreadStream>());
    // A deadline, so that a server that never drops them cannot hang the
    // test; far beyond the 10 s stall, since a loaded machine (CI runs other
    // builds beside) may take long to reach the first write of each.
    streams.back()->context.set_deadline(std::chrono::system_clock::now() + seconds(150));
    streams.back()->reader =
        stub->StreamPoints(&streams.back()->context, StreamRequest({0, 0, 4000, 4000}));
  }
  // The event: every stream admitted (a first chunk) or shed (ended), and
  // then nothing more read.
  int admitted = 0;
  for (auto& stream : streams) {
    v1::PointsChunk chunk;
    if (stream->reader->Read(&chunk)) ++admitted;
  }
  EXPECT_GT(admitted, 0);
  // Unary calls have their own slots.
  for (int k = 0; k < 3; ++k) {
    const grpc::Status status = SmallGetPoints(client);
    EXPECT_TRUE(status.ok()) << client::DescribeStatus(status);
  }
  // The event: a stream slot comes free (the stall timer, 10 s by default,
  // has dropped the unread ones).
  grpc::Status fresh;
  const auto deadline = std::chrono::steady_clock::now() + seconds(120);
  do {
    fresh = client.StreamPoints(StreamRequest({0, 0, 20, 20}),
                                [](const v1::PointsChunk&) { return true; });
  } while (!fresh.ok() && std::chrono::steady_clock::now() < deadline &&
           (std::this_thread::sleep_for(milliseconds(100)), true));
  EXPECT_TRUE(fresh.ok()) << client::DescribeStatus(fresh);
  // The event: every admitted stream has been dropped for stalling, still
  // unread (the drain below reads what is left, so a stream it reached before
  // its stall timer fired would run to its end instead).
  const std::string stalled_key =
      "scallop_requests_total{method=\"StreamPoints\",code=\"DEADLINE_EXCEEDED\"}";
  while (ScrapeMetrics(metrics)[stalled_key] < admitted &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(milliseconds(100));
  }
  // Each unread stream was either shed at once or dropped for stalling.
  int stalled = 0, shed = 0;
  for (auto& stream : streams) {
    v1::PointsChunk chunk;
    while (stream->reader->Read(&chunk)) {
    }
    const grpc::Status status = stream->reader->Finish();
    if (status.error_code() == grpc::StatusCode::DEADLINE_EXCEEDED &&
        status.error_message().find("stream_stall_seconds") != std::string::npos) {
      ++stalled;
    } else if (status.error_code() == grpc::StatusCode::RESOURCE_EXHAUSTED) {
      ++shed;
    } else {
      ADD_FAILURE() << client::DescribeStatus(status);
    }
  }
  EXPECT_EQ(stalled + shed, 64);
  EXPECT_EQ(stalled, admitted);
}

v1::FollowRequest FirstUpdate() {
  v1::FollowRequest update;
  *update.mutable_world() = WorldToMessage(ValidWorld({.seed = 32}));
  *update.mutable_viewport() = RectToMessage({0, 0, 30, 30});
  return update;
}

// Followers that got their first answer and then sent nothing: dropped after
// follow_idle_seconds, with a status that says so.
TEST(E2eStreamSlotsTest, IdleFollowersAreDroppedAndTakeNoUnarySlot) {
  const std::string config = ::testing::TempDir() + "e2e_stream_slots.yaml";
  // Not a round number: messages print it exactly (std::to_string said 1).
  // The whole stream budget for this one client: the test is of idling.
  std::ofstream(config) << "follow_idle_seconds: 1.0000001\nmax_streams_in_flight: 2\n"
                        << "max_client_share: 1\n"
                        << "max_in_flight: 2\n";
  auto server = ScallopdProcess::Start({"--config", config});
  ASSERT_NE(server, nullptr);
  client::ScallopClient client = server->Client();
  std::vector<std::unique_ptr<client::FollowSession>> idle;
  for (int k = 0; k < 2; ++k) {
    idle.push_back(std::make_unique<client::FollowSession>(client));
    const grpc::Status status = idle.back()->Update(FirstUpdate(), [](const auto&) {});
    ASSERT_TRUE(status.ok()) << client::DescribeStatus(status);
  }
  const grpc::Status unary = SmallGetPoints(client);
  EXPECT_TRUE(unary.ok()) << client::DescribeStatus(unary);
  // The event: a new follower is admitted once the idle ones are dropped.
  grpc::Status fresh;
  const auto deadline = std::chrono::steady_clock::now() + seconds(30);
  do {
    client::FollowSession session(client);
    fresh = session.Update(FirstUpdate(), [](const auto&) {});
  } while (!fresh.ok() && std::chrono::steady_clock::now() < deadline &&
           (std::this_thread::sleep_for(milliseconds(100)), true));
  EXPECT_TRUE(fresh.ok()) << client::DescribeStatus(fresh);
  for (auto& session : idle) {
    v1::FollowRequest next;
    *next.mutable_viewport() = RectToMessage({5, 5, 35, 35});
    const grpc::Status status = session->Update(next, [](const auto&) {});
    EXPECT_EQ(status.error_code(), grpc::StatusCode::DEADLINE_EXCEEDED)
        << client::DescribeStatus(status);
    EXPECT_NE(status.error_message().find("1.0000001 s (follow_idle_seconds)"), std::string::npos)
        << status.error_message();
  }
  std::remove(config.c_str());
}

}  // namespace
}  // namespace scallop::testing
