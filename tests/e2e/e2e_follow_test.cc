// End to end: Follow against the real scallopd. On random walks with
// reversals, teleports and zoom changes, every point in view is held after
// each update, bit for bit as the core computes it, none arrives twice while
// its region is kept, evictions name exactly the regions left behind, and the
// union received is the world over the path. Held regions are not sent; a
// client that stops reading is dropped with a clear status; bad updates get
// the code and a message naming the field.
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <thread>

#include "follow_client.h"
#include "scallop/plane/plane_engine.h"
#include "scallop/plane/point_id.h"
#include "scallop/random/rng.h"
#include "tests/e2e/scallopd_process.h"
#include "tests/test_worlds.h"
#include "world_messages.h"

namespace scallop::testing {
namespace {

constexpr double kStallSeconds = 0.5;
constexpr double kMaxFollowArea = 40000;

// A config file for the suite's server: a short stall limit keeps the
// stalled-client test fast.
std::string WriteConfig() {
  const std::string path = ::testing::TempDir() + "/e2e_follow_config.yaml";
  std::ofstream(path) << "follow_stall_seconds: " << kStallSeconds
                      << "\nmax_follow_area: " << kMaxFollowArea << "\n";
  return path;
}

class E2eFollowTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    server_ =
        ScallopdProcess::Start({"--config", WriteConfig(), "--world", "coast:7:1:a3"}).release();
  }
  static void TearDownTestSuite() {
    delete server_;
    server_ = nullptr;
  }
  void SetUp() override { ASSERT_NE(server_, nullptr) << "scallopd did not start"; }

  static ScallopdProcess* server_;
};
ScallopdProcess* E2eFollowTest::server_ = nullptr;

v1::FollowRequest Update(const Rect& viewport, double keep_margin = 0, Vec2 velocity = {}) {
  v1::FollowRequest request;
  *request.mutable_viewport() = RectToMessage(viewport);
  request.set_keep_margin(keep_margin);
  request.set_velocity_x(velocity.x);
  request.set_velocity_y(velocity.y);
  return request;
}

bool Overlaps(const Rect& a, const Rect& b) {
  return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

// Whether region `key` is kept for `viewport` grown by `margin`, from the
// region's own rectangle (independent of the server's index arithmetic).
bool Kept(const World& world, RegionKey key, const Rect& viewport, double margin) {
  const Rect grown{viewport.x0 - margin, viewport.y0 - margin, viewport.x1 + margin,
                   viewport.y1 + margin};
  return Overlaps(RegionLayout(world).RegionRect(key), grown);
}

// A follower checking every answer against the core; failures are reported
// through gtest with the step. Returns the ids received, for the union check.
class CheckedFollower {
 public:
  CheckedFollower(client::FollowSession& session, const World& world, PlaneEngine& engine)
      : session_(session), world_(world), engine_(engine) {}

  client::FollowedPoints& points() { return points_; }

  // One update; false when the call failed (the status is in `status`).
  bool Step(v1::FollowRequest request, const std::string& where, grpc::Status* status = nullptr) {
    const Rect viewport = RectFromMessage(request.viewport());
    const double margin = request.keep_margin();
    const std::vector<RegionKey> before = points_.Regions();
    std::set<RegionKey> evicted;
    const grpc::Status result =
        session_.Update(std::move(request), [&](const v1::FollowResponse& response) {
          for (const v1::RegionKey& key : response.evicted()) evicted.insert({key.i(), key.j()});
          if (response.has_chunk()) {
            const v1::PointsChunk& chunk = response.chunk();
            const RegionKey key{chunk.region_i(), chunk.region_j()};
            for (int k = 0; k < chunk.points().ids_size(); ++k) {
              const uint64_t id = chunk.points().ids(k);
              EXPECT_FALSE(points_.Holds(key, id) && !evicted.contains(key))
                  << where << ": point " << id << " sent twice while its region was kept";
              EXPECT_EQ(DecodePointId(id, key).region, key) << where << ": id in wrong chunk";
              received_.insert(id);
            }
          }
          EXPECT_TRUE(points_.Apply(response).ok()) << where;
        });
    if (status != nullptr) *status = result;
    if (!result.ok()) return false;
    // Evictions are exactly the regions held before and no longer kept.
    for (const RegionKey& key : before) {
      EXPECT_EQ(evicted.contains(key), !Kept(world_, key, viewport, margin))
          << where << ": region " << key.i << "," << key.j;
    }
    for (const RegionKey& key : evicted) {
      EXPECT_TRUE(std::find(before.begin(), before.end(), key) != before.end())
          << where << ": evicted a region never held";
    }
    // Every point in view is held, at the core's exact position.
    StatusOr<PlanePoints> in_view = engine_.Points(world_, viewport);
    EXPECT_TRUE(in_view.ok()) << in_view.status().message();
    if (!in_view.ok()) return false;
    in_view_union_.insert(in_view->ids.begin(), in_view->ids.end());
    std::map<uint64_t, Vec2> held;
    for (const RegionKey& key : points_.Regions()) {
      EXPECT_TRUE(Kept(world_, key, viewport, margin)) << where << ": holds an unkept region";
      const PlanePoints& p = points_.PointsOf(key);
      for (size_t k = 0; k < p.ids.size(); ++k) held[p.ids[k]] = p.positions[k];
    }
    int missing = 0, moved = 0;
    for (size_t k = 0; k < in_view->ids.size(); ++k) {
      const auto it = held.find(in_view->ids[k]);
      if (it == held.end()) {
        ++missing;
      } else if (std::bit_cast<uint64_t>(it->second.x) !=
                     std::bit_cast<uint64_t>(in_view->positions[k].x) ||
                 std::bit_cast<uint64_t>(it->second.y) !=
                     std::bit_cast<uint64_t>(in_view->positions[k].y)) {
        ++moved;
      }
    }
    EXPECT_EQ(missing, 0) << where << ": points in view not held";
    EXPECT_EQ(moved, 0) << where << ": points held at another position";
    return true;
  }

  const std::set<uint64_t>& received() const { return received_; }
  const std::set<uint64_t>& in_view_union() const { return in_view_union_; }

 private:
  client::FollowSession& session_;
  World world_;
  PlaneEngine& engine_;
  client::FollowedPoints points_;
  std::set<uint64_t> received_, in_view_union_;
};

TEST_F(E2eFollowTest, RandomWalksMatchTheWorldOverThePath) {
  PlaneEngine engine({.threads = 2});
  for (uint64_t seed = 1; seed <= 3; ++seed) {
    const World world =
        ValidWorld({.seed = seed * 1000 + 3, .min_distance = seed == 2 ? 0.25 : 1.0});
    const double d = world.min_distance();
    Rng rng(HashWords({seed, 8}));
    const client::ScallopClient client = server_->Client();
    client::FollowSession session(client);
    CheckedFollower follower(session, world, engine);
    double w = 40 * d, h = 30 * d, cx = 0, cy = 0;
    Vec2 v{rng.Uniform(-4, 4) * d, rng.Uniform(-4, 4) * d};
    for (int step = 0; step < 40; ++step) {
      switch (rng.Below(10)) {
        case 0:  // teleport
          cx = rng.Uniform(-1e5, 1e5) * d;
          cy = rng.Uniform(-1e5, 1e5) * d;
          break;
        case 1:  // reversal
          v = {-v.x, -v.y};
          break;
        case 2:  // zoom
          w = std::clamp(w * rng.Uniform(0.5, 2), 2 * d, 100 * d);
          h = std::clamp(h * rng.Uniform(0.5, 2), 2 * d, 100 * d);
          break;
        default:
          break;
      }
      cx += v.x;
      cy += v.y;
      const Rect viewport{cx - w / 2, cy - h / 2, cx + w / 2, cy + h / 2};
      const double margin = rng.Below(3) == 0 ? 0 : rng.Uniform(0, 20) * d;
      v1::FollowRequest request = Update(viewport, margin, {v.x * 30, v.y * 30});
      if (step == 0) *request.mutable_world() = WorldToMessage(world);
      const std::string where = "seed " + std::to_string(seed) + " step " + std::to_string(step);
      grpc::Status status;
      ASSERT_TRUE(follower.Step(request, where, &status)) << client::DescribeStatus(status);
    }
    EXPECT_EQ(follower.received(), follower.in_view_union()) << "seed " << seed;
    EXPECT_TRUE(session.Finish().ok());
  }
}

// Whether `step` reports a failure whose message contains `part`; its
// failures are captured instead of failing the calling test.
bool ReportsFailure(const std::function<void()>& step, const std::string& part) {
  ::testing::TestPartResultArray results;
  {
    const ::testing::ScopedFakeTestPartResultReporter reporter(
        ::testing::ScopedFakeTestPartResultReporter::INTERCEPT_ONLY_CURRENT_THREAD, &results);
    step();
  }
  for (int n = 0; n < results.size(); ++n) {
    if (std::string(results.GetTestPartResult(n).message()).find(part) != std::string::npos) {
      return true;
    }
  }
  return false;
}

// Each check of CheckedFollower catches a fault planted in a real call: the
// follower's store is made to disagree with what the server knows.
TEST_F(E2eFollowTest, ChecksCatchPlantedFaults) {
  const World world = ValidWorld({.seed = 31});
  PlaneEngine engine({.threads = 1});
  const client::ScallopClient client = server_->Client();
  auto region_points = [&](RegionKey key) {
    PlanePoints points;
    const StatusOr<RegionHandle> region = engine.Region(world, key);
    for (size_t k = 0; k < (*region)->points.size(); ++k) {
      points.positions.push_back((*region)->points[k]);
      points.ids.push_back(EncodePointId(key, static_cast<uint32_t>(k)));
    }
    return points;
  };
  v1::FollowRequest first = Update({0, 0, 40, 40});
  *first.mutable_world() = WorldToMessage(world);
  {
    // Declared held but not held: points in view are missing.
    client::FollowSession session(client);
    CheckedFollower follower(session, world, engine);
    v1::FollowRequest request = first;
    v1::RegionKey& held = *request.add_held_regions();
    held.set_i(1);
    held.set_j(1);
    EXPECT_TRUE(
        ReportsFailure([&] { follower.Step(request, "planted"); }, "points in view not held"));
  }
  {
    // Held but not declared: the server sends its points, seen as sent twice.
    client::FollowSession session(client);
    CheckedFollower follower(session, world, engine);
    follower.points().AddRegion({1, 1}, region_points({1, 1}));
    EXPECT_TRUE(ReportsFailure([&] { follower.Step(first, "planted"); }, "sent twice"));
  }
  {
    // Held far away without the server knowing: its eviction never comes.
    client::FollowSession session(client);
    CheckedFollower follower(session, world, engine);
    follower.points().AddRegion({50, 50}, region_points({50, 50}));
    EXPECT_TRUE(ReportsFailure([&] { follower.Step(first, "planted"); }, "region 50,50"));
  }
}

// A named world gives the points of its inline twin.
TEST_F(E2eFollowTest, NamedWorldIsItsInlineTwin) {
  PlaneEngine engine({.threads = 1});
  const client::ScallopClient client = server_->Client();
  client::FollowSession session(client);
  CheckedFollower follower(session, ValidWorld({.seed = 7}), engine);
  v1::FollowRequest first = Update({-20, -20, 30, 25});
  first.set_world_name("coast");
  ASSERT_TRUE(follower.Step(first, "named"));
  ASSERT_TRUE(follower.Step(Update({-10, -20, 40, 25}), "named, moved"));
  EXPECT_GT(follower.received().size(), 1000u);
}

// A resumed session names the whole regions it holds: none of their points
// comes again, and held plus received is the world in view.
TEST_F(E2eFollowTest, HeldRegionsAreNotSentAgain) {
  const World world = ValidWorld({.seed = 21});
  PlaneEngine engine({.threads = 1});
  const client::ScallopClient client = server_->Client();
  client::FollowedPoints cache;
  {
    // [0, 64)^2 is exactly regions (0..3, 0..3): the follower ends with them whole.
    client::FollowSession first(client);
    v1::FollowRequest request = Update({0, 0, 64, 64});
    *request.mutable_world() = WorldToMessage(world);
    ASSERT_TRUE(first.Update(request, [&](const v1::FollowResponse& r) { cache.Apply(r); }).ok());
    EXPECT_TRUE(first.Finish().ok());
  }
  ASSERT_EQ(cache.Regions().size(), 16u);
  client::FollowSession resumed(client);
  v1::FollowRequest request = Update({-8, -8, 72, 72});
  *request.mutable_world() = WorldToMessage(world);
  for (const RegionKey& key : cache.Regions()) {
    v1::RegionKey& held = *request.add_held_regions();
    held.set_i(key.i);
    held.set_j(key.j);
  }
  // A held region far away is ignored, not evicted.
  v1::RegionKey& far = *request.add_held_regions();
  far.set_i(1000);
  far.set_j(-1000);
  std::set<uint64_t> received;
  bool evicted_any = false;
  ASSERT_TRUE(resumed
                  .Update(request,
                          [&](const v1::FollowResponse& response) {
                            evicted_any |= response.evicted_size() > 0;
                            const v1::PointsChunk& chunk = response.chunk();
                            EXPECT_FALSE(chunk.region_i() >= 0 && chunk.region_i() <= 3 &&
                                         chunk.region_j() >= 0 && chunk.region_j() <= 3)
                                << "a held region was sent";
                            for (uint64_t id : chunk.points().ids()) received.insert(id);
                          })
                  .ok());
  EXPECT_FALSE(evicted_any);
  std::set<uint64_t> expected;
  const StatusOr<PlanePoints> in_view = engine.Points(world, {-8, -8, 72, 72});
  ASSERT_TRUE(in_view.ok());
  expected.insert(in_view->ids.begin(), in_view->ids.end());
  for (const RegionKey& key : cache.Regions()) {
    for (uint64_t id : cache.PointsOf(key).ids) {
      EXPECT_TRUE(received.insert(id).second) << "held point " << id << " received";
    }
  }
  EXPECT_EQ(received, expected);
  // Moving away evicts the held regions too.
  std::set<RegionKey> evicted;
  ASSERT_TRUE(resumed
                  .Update(Update({500, 500, 520, 520}),
                          [&](const v1::FollowResponse& response) {
                            for (const v1::RegionKey& key : response.evicted()) {
                              evicted.insert({key.i(), key.j()});
                            }
                          })
                  .ok());
  for (const RegionKey& key : cache.Regions()) EXPECT_TRUE(evicted.contains(key));
}

// The client sends updates and never reads: once the transport's buffers are
// full a write cannot complete, and after follow_stall_seconds the server
// ends the call with DEADLINE_EXCEEDED and says why.
TEST_F(E2eFollowTest, AClientThatStopsReadingIsDropped) {
  const client::ScallopClient client = server_->Client();
  client::FollowSession session(client);
  // Back and forth between two large views far apart: each move evicts the
  // other view, so every answer is a full view of points (about 750 kB), and
  // after the first two the regions are cached, so answers come fast.
  const auto start = std::chrono::steady_clock::now();
  for (int n = 0; n < 40; ++n) {
    const double x = n % 2 == 0 ? 0.0 : 5000.0;
    v1::FollowRequest request = Update({x, 0, x + 190, 190});
    if (n == 0) *request.mutable_world() = WorldToMessage(ValidWorld({.seed = 5}));
    if (!session.SendOnly(request)) break;
  }
  // Not reading until the server has dropped the call (its log says so):
  // Finish reads what is left, so it must come after. The wait ends on the
  // event, not on a guess of how fast this machine fills its buffers.
  while (server_->Log().find("follow_stall_seconds") == std::string::npos &&
         std::chrono::steady_clock::now() - start < std::chrono::seconds(30)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  const grpc::Status status = session.Finish();
  EXPECT_EQ(status.error_code(), grpc::StatusCode::DEADLINE_EXCEEDED)
      << client::DescribeStatus(status);
  EXPECT_NE(status.error_message().find("follow_stall_seconds"), std::string::npos)
      << status.error_message();
  // The server is still serving others.
  client::FollowSession other(client);
  EXPECT_TRUE(other.Update(Update({0, 0, 10, 10}), [](const v1::FollowResponse&) {}).ok());
}

TEST_F(E2eFollowTest, BadUpdatesNameTheField) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  using enum grpc::StatusCode;
  struct Case {
    const char* name;
    v1::FollowRequest first;   // sent first (with the world)
    v1::FollowRequest second;  // sent next, unless it has no viewport and no world
    bool send_second;
    grpc::StatusCode code;
    const char* message_part;
  };
  const v1::FollowRequest good = Update({0, 0, 10, 10});
  auto with = [](v1::FollowRequest request, auto change) {
    change(request);
    return request;
  };
  const std::vector<Case> cases{
      {"nan corner",
       with(good, [&](auto& r) { r.mutable_viewport()->set_x0(nan); }),
       {},
       false,
       INVALID_ARGUMENT,
       "viewport.x0: must be finite"},
      {"inverted",
       Update({10, 0, 0, 10}),
       {},
       false,
       INVALID_ARGUMENT,
       "viewport: x0 must be less"},
      {"missing viewport", v1::FollowRequest(), {}, false, INVALID_ARGUMENT, "viewport: required"},
      {"beyond the range",
       Update({0x1.0p33, 0, 0x1.0p33 + 10, 10}),
       {},
       false,
       OUT_OF_RANGE,
       "viewport.x0"},
      {"area over the limit",
       Update({0, 0, 300, 300}),
       {},
       false,
       INVALID_ARGUMENT,
       "max_follow_area"},
      {"margin over the limit",
       Update({0, 0, 10, 10}, 200),
       {},
       false,
       INVALID_ARGUMENT,
       "max_follow_area"},
      {"negative margin", Update({0, 0, 10, 10}, -1), {}, false, INVALID_ARGUMENT, "keep_margin"},
      {"nan velocity",
       with(good, [&](auto& r) { r.set_velocity_y(nan); }),
       {},
       false,
       INVALID_ARGUMENT,
       "velocity_y: must be finite"},
      {"bad inline world",
       with(good,
            [](auto& r) {
              *r.mutable_world() = WorldToMessage(World());
              r.mutable_world()->set_min_distance(-1);
            }),
       {},
       false,
       INVALID_ARGUMENT,
       "world.min_distance"},
      {"unknown world name",
       with(good, [](auto& r) { r.set_world_name("atlantis"); }),
       {},
       false,
       NOT_FOUND,
       "world_name"},
      {"world in a later message", good, with(good, [](auto& r) { r.set_world_name("coast"); }),
       true, INVALID_ARGUMENT, "world: set only in the first message"},
      {"bad later viewport", good, Update({0, 5, 10, 5}), true, INVALID_ARGUMENT,
       "viewport: y0 must be less"},
  };
  const client::ScallopClient client = server_->Client();
  for (const Case& c : cases) {
    client::FollowSession session(client);
    grpc::Status status = session.Update(c.first, [](const v1::FollowResponse&) {});
    if (c.send_second) {
      ASSERT_TRUE(status.ok()) << c.name << ": " << client::DescribeStatus(status);
      status = session.Update(c.second, [](const v1::FollowResponse&) {});
    }
    EXPECT_EQ(status.error_code(), c.code) << c.name << ": " << client::DescribeStatus(status);
    EXPECT_NE(status.error_message().find(c.message_part), std::string::npos)
        << c.name << ": " << status.error_message();
  }
}

}  // namespace
}  // namespace scallop::testing
