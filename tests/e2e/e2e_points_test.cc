// End to end: the same points, bit for bit and with the same ids, from
// GetPoints in one page, in many pages, from StreamPoints, from the core
// directly, from two server processes, and across a restart.
#include <gtest/gtest.h>
#include <signal.h>

#include <bit>
#include <cmath>
#include <thread>

#include "scallop/plane/plane_engine.h"
#include "tests/e2e/scallopd_process.h"
#include "tests/test_worlds.h"
#include "world_messages.h"

namespace scallop::testing {
namespace {

using std::chrono::milliseconds;

const std::vector<std::string> kServerArguments{
    "--world", "coast:7:1:a3", "--world", "dense:11:0.5:a1:1.5", "--threads", "2"};

// Positions compared as bits, so -0.0 and 0.0 or a last-bit change all count.
::testing::AssertionResult SamePoints(const PlanePoints& expected, const PlanePoints& actual) {
  if (expected.positions.size() != actual.positions.size() ||
      actual.ids.size() != actual.positions.size()) {
    return ::testing::AssertionFailure()
           << "sizes " << expected.positions.size() << " and " << actual.positions.size();
  }
  for (size_t k = 0; k < expected.positions.size(); ++k) {
    if (expected.ids[k] != actual.ids[k] ||
        std::bit_cast<uint64_t>(expected.positions[k].x) !=
            std::bit_cast<uint64_t>(actual.positions[k].x) ||
        std::bit_cast<uint64_t>(expected.positions[k].y) !=
            std::bit_cast<uint64_t>(actual.positions[k].y)) {
      return ::testing::AssertionFailure() << "point " << k << " differs";
    }
  }
  return ::testing::AssertionSuccess();
}

void ExpectSamePoints(const PlanePoints& expected, const PlanePoints& actual, const char* what) {
  EXPECT_TRUE(SamePoints(expected, actual)) << what;
}

PlanePoints CorePoints(const World& world, const Rect& rect) {
  PlaneEngine engine({.threads = 1});
  StatusOr<PlanePoints> points = engine.Points(world, rect);
  EXPECT_TRUE(points.ok()) << points.status().message();
  return points.ok() ? *points : PlanePoints{};
}

template <typename Request>
Request RequestFor(const World& world, const Rect& rect) {
  Request request;
  *request.mutable_world() = WorldToMessage(world);
  *request.mutable_rect() = RectToMessage(rect);
  return request;
}

class E2ePointsTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { server_ = ScallopdProcess::Start(kServerArguments).release(); }
  static void TearDownTestSuite() { delete server_; }
  void SetUp() override { ASSERT_NE(server_, nullptr); }

  static ScallopdProcess* server_;
};
ScallopdProcess* E2ePointsTest::server_ = nullptr;

TEST(E2eComparisonTest, CatchesPlantedFaults) {
  const PlanePoints points = CorePoints(ValidWorld({.seed = 4}), {0, 0, 20, 20});
  ASSERT_GT(points.ids.size(), 10u);
  EXPECT_TRUE(SamePoints(points, points));
  PlanePoints last_bit = points;
  last_bit.positions[5].y = std::nextafter(last_bit.positions[5].y, 1e9);
  EXPECT_FALSE(SamePoints(points, last_bit));
  PlanePoints swapped = points;
  std::swap(swapped.ids[2], swapped.ids[3]);
  EXPECT_FALSE(SamePoints(points, swapped));
  PlanePoints missing = points;
  missing.positions.pop_back();
  missing.ids.pop_back();
  EXPECT_FALSE(SamePoints(points, missing));
}

TEST_F(E2ePointsTest, UnaryPagedStreamedAndCoreAgree) {
  // Corners off the region grid, so every query cuts regions at all four sides.
  const Rect rect{-37.25, -20.5, 41.75, 50.125};
  for (const World& world :
       {ValidWorld({.seed = 7, .algorithm = WorldAlgorithm::kA3}),
        ValidWorld(
            {.seed = 11, .min_distance = 0.5, .algorithm = WorldAlgorithm::kA1, .density = 1.5}),
        ValidWorld({.seed = 3, .algorithm = WorldAlgorithm::kA2})}) {
    SCOPED_TRACE(world.Describe());
    const PlanePoints core = CorePoints(world, rect);
    ASSERT_GT(core.ids.size(), 1000u);
    client::ScallopClient client = server_->Client();

    v1::GetPointsResponse single;
    ASSERT_TRUE(client.GetPoints(RequestFor<v1::GetPointsRequest>(world, rect), single).ok());
    EXPECT_TRUE(single.next_page_token().empty());
    PlanePoints unary;
    ASSERT_TRUE(ReadPoints(single.points(), unary).ok());
    ExpectSamePoints(core, unary, "unary");

    auto paged_request = RequestFor<v1::GetPointsRequest>(world, rect);
    paged_request.set_page_size(97);  // prime, so pages never line up with regions
    PlanePoints paged;
    ASSERT_TRUE(client.GetAllPoints(paged_request, paged).ok());
    ExpectSamePoints(core, paged, "paged");

    PlanePoints streamed;
    int chunks = 0;
    grpc::Status status = client.StreamPoints(
        RequestFor<v1::StreamPointsRequest>(world, rect), [&](const v1::PointsChunk& chunk) {
          ++chunks;
          EXPECT_LE(chunk.points().ids_size(), 296);  // at most one region's points
          return ReadPoints(chunk.points(), streamed).ok();
        });
    ASSERT_TRUE(status.ok()) << client::DescribeStatus(status);
    EXPECT_GT(chunks, 20);
    ExpectSamePoints(core, streamed, "streamed");
  }
}

TEST_F(E2ePointsTest, NamedWorldEqualsItsInlineTwin) {
  const Rect rect{0, 0, 40, 40};
  v1::GetPointsRequest request;
  request.set_world_name("dense");
  *request.mutable_rect() = RectToMessage(rect);
  PlanePoints named;
  ASSERT_TRUE(server_->Client().GetAllPoints(request, named).ok());
  const World dense = ValidWorld(
      {.seed = 11, .min_distance = 0.5, .algorithm = WorldAlgorithm::kA1, .density = 1.5});
  ExpectSamePoints(CorePoints(dense, rect), named, "named");
}

TEST_F(E2ePointsTest, DescribeWorldAndServerInfo) {
  client::ScallopClient client = server_->Client();
  v1::DescribeWorldRequest describe;
  describe.set_world_name("coast");
  v1::DescribeWorldResponse world;
  ASSERT_TRUE(client.DescribeWorld(describe, world).ok());
  EXPECT_EQ(world.name(), "coast");
  EXPECT_EQ(world.world().seed(), 7u);
  EXPECT_EQ(world.world().algorithm(), v1::ALGORITHM_A3);
  EXPECT_EQ(world.world().density(), 2.0);
  EXPECT_EQ(world.world().generator_version(), kGeneratorVersion);
  EXPECT_EQ(world.region_side(), 16.0);
  EXPECT_EQ(world.precision_limit(), 0x1.0p32);
  EXPECT_EQ(world.fingerprint(), ValidWorld({.seed = 7}).fingerprint());

  v1::DescribeWorldRequest default_world;  // no world: the server's default
  ASSERT_TRUE(client.DescribeWorld(default_world, world).ok());
  EXPECT_EQ(world.name(), "default");

  v1::GetServerInfoResponse info;
  ASSERT_TRUE(client.GetServerInfo(info).ok());
  EXPECT_EQ(info.generator_version(), kGeneratorVersion);
  EXPECT_EQ(info.precision_range_in_d(), 0x1.0p32);
  EXPECT_EQ(info.region_side_in_d(), 16.0);
  EXPECT_EQ(info.field_region_side_in_r_max(), 6.0);
  EXPECT_EQ(info.limits().max_page_size(), 65536);
  EXPECT_EQ(info.default_world(), "default");
  EXPECT_EQ(std::vector<std::string>(info.world_names().begin(), info.world_names().end()),
            (std::vector<std::string>{"coast", "default", "dense"}));
}

TEST_F(E2ePointsTest, ConcurrentCallsForTheSameColdRegionsAgree) {
  // Eight clients at once on regions nobody asked for yet: they share the
  // generation (one region cache) and must all see the same points.
  const World world = ValidWorld({.seed = 77, .algorithm = WorldAlgorithm::kA2});
  const Rect rect{-500, 300, -400, 400};
  const PlanePoints core = CorePoints(world, rect);
  std::vector<PlanePoints> answers(8);
  std::vector<grpc::Status> statuses(8);
  std::vector<std::thread> clients;
  for (size_t k = 0; k < answers.size(); ++k) {
    clients.emplace_back([&, k] {
      client::ScallopClient client = server_->Client();
      if (k % 2 == 0) {
        statuses[k] =
            client.GetAllPoints(RequestFor<v1::GetPointsRequest>(world, rect), answers[k]);
      } else {
        statuses[k] =
            client.StreamAllPoints(RequestFor<v1::StreamPointsRequest>(world, rect), answers[k]);
      }
    });
  }
  for (std::thread& client : clients) client.join();
  for (size_t k = 0; k < answers.size(); ++k) {
    ASSERT_TRUE(statuses[k].ok()) << client::DescribeStatus(statuses[k]);
    ExpectSamePoints(core, answers[k], k % 2 == 0 ? "concurrent unary" : "concurrent stream");
  }
}

// Issue 20: -0 and +0 name the same rectangle, so a token minted for one
// pages the other (the old server refused it as made for another rect).
TEST_F(E2ePointsTest, APageTokenForZeroPagesNegativeZero) {
  client::ScallopClient client = server_->Client();
  auto request = RequestFor<v1::GetPointsRequest>(ValidWorld({.seed = 51}), {0, 0, 40, 40});
  request.set_page_size(100);
  v1::GetPointsResponse first;
  ASSERT_TRUE(client.GetPoints(request, first).ok());
  ASSERT_FALSE(first.next_page_token().empty());
  auto negative = RequestFor<v1::GetPointsRequest>(ValidWorld({.seed = 51}), {-0.0, -0.0, 40, 40});
  ASSERT_TRUE(std::signbit(negative.rect().x0()));
  negative.set_page_size(100);
  negative.set_page_token(first.next_page_token());
  v1::GetPointsResponse second;
  const grpc::Status status = client.GetPoints(negative, second);
  ASSERT_TRUE(status.ok()) << client::DescribeStatus(status);
  request.set_page_token(first.next_page_token());
  v1::GetPointsResponse expected;
  ASSERT_TRUE(client.GetPoints(request, expected).ok());
  EXPECT_EQ(second.points().ids(0), expected.points().ids(0));
}

TEST(E2eReplicasTest, TwoServersAndARestartGiveTheSamePointsAndAcceptEachOthersTokens) {
  const Rect rect{-100, -60, 60, 100};
  auto first = ScallopdProcess::Start(kServerArguments);
  auto second = ScallopdProcess::Start(kServerArguments);
  ASSERT_NE(first, nullptr);
  ASSERT_NE(second, nullptr);
  v1::GetPointsRequest request;
  request.set_world_name("coast");
  *request.mutable_rect() = RectToMessage(rect);
  request.set_page_size(1000);
  PlanePoints from_first, from_second;
  ASSERT_TRUE(first->Client().GetAllPoints(request, from_first).ok());
  ASSERT_TRUE(second->Client().GetAllPoints(request, from_second).ok());
  ExpectSamePoints(from_first, from_second, "two servers");

  // A page token from one replica continues on the other, and after a restart.
  v1::GetPointsResponse page;
  ASSERT_TRUE(first->Client().GetPoints(request, page).ok());
  ASSERT_FALSE(page.next_page_token().empty());
  request.set_page_token(page.next_page_token());
  v1::GetPointsResponse on_second;
  ASSERT_TRUE(second->Client().GetPoints(request, on_second).ok());
  EXPECT_EQ(on_second.points().ids(0), from_first.ids[1000]);

  first->Signal(SIGTERM);
  ASSERT_EQ(first->WaitForExit(milliseconds(15000)), 0);
  first = ScallopdProcess::Start(kServerArguments);
  ASSERT_NE(first, nullptr);
  v1::GetPointsResponse after_restart;
  ASSERT_TRUE(first->Client().GetPoints(request, after_restart).ok());
  EXPECT_EQ(after_restart.points().ids(0), from_first.ids[1000]);
  request.clear_page_token();
  PlanePoints restarted;
  ASSERT_TRUE(first->Client().GetAllPoints(request, restarted).ok());
  ExpectSamePoints(from_first, restarted, "after restart");
}

}  // namespace
}  // namespace scallop::testing
