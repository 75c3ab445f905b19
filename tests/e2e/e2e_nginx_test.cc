// End to end behind a real balancer: deploy/nginx/scallop.conf, as shipped but
// for its addresses and paths, run by Debian's nginx in front of three
// scallopd replicas sharing one page-token secret. Calls through nginx answer
// exactly as a single direct server; nginx's access log (upstream=...) and the
// replicas' /metrics show that different replicas served them. A replica is
// killed mid-call and restarted: unary calls succeed through the client's
// retries, a broken stream ends with a status and resumes where it stopped.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <thread>

#include "follow_client.h"
#include "scallop/plane/point_id.h"
#include "stream_resume.h"
#include "tests/e2e/metrics_scrape.h"
#include "tests/e2e/nginx_process.h"
#include "tests/e2e/scallopd_process.h"
#include "world_messages.h"

namespace scallop::testing {
namespace {

constexpr int kReplicas = 3;
constexpr int kNginxGrpcPort = 8080;  // the `listen`s of deploy/nginx/scallop.conf
constexpr int kNginxHttpPort = 8090;
// Every replica gets this: tokens minted by one must page on the others.
const std::vector<std::string> kReplicaArguments{"--world",
                                                 "coast:7:1:a3",
                                                 "--world",
                                                 "hills:11:1:a1",
                                                 "--default-world",
                                                 "coast",
                                                 "--metrics-listen",
                                                 "127.0.0.1:0",
                                                 "--page-token-secret",
                                                 "e2e-nginx-shared-secret",
                                                 "--threads",
                                                 "1"};

// One line of nginx's access log (log_format scallop_grpc).
struct AccessLine {
  std::string method;  // "GetPoints"
  int status = 0;
  std::string upstream;  // "127.0.0.1:PORT" or several, ", "-separated, when nginx tried more
  std::string connection;
};

std::vector<AccessLine> ParseAccessLog(const std::string& text) {
  static const std::regex line_pattern(
      R"re("POST /scallop\.v1\.Scallop/(\w+) [^"]*" (\d+) \S+ upstream=(.*) connection=(\d+) )re");
  std::vector<AccessLine> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::smatch match;
    if (std::regex_search(line, match, line_pattern)) {
      lines.push_back({match[1], std::stoi(match[2]), match[3], match[4]});
    }
  }
  return lines;
}

// nginx's access log once it holds at least `count` lines, polled for 10 s (then as it is):
// nginx writes a call's line after the call ends, which under load can be after the client
// has its answer.
std::vector<AccessLine> AccessLogOnceItHas(const NginxProcess& nginx, size_t count) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  std::vector<AccessLine> lines = ParseAccessLog(nginx.ReadFile("scallop-grpc.log"));
  while (lines.size() < count && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    lines = ParseAccessLog(nginx.ReadFile("scallop-grpc.log"));
  }
  return lines;
}

v1::GetPointsRequest PointsRequest(const std::string& world, const Rect& rect, int page_size = 0) {
  v1::GetPointsRequest request;
  request.set_world_name(world);
  *request.mutable_rect() = RectToMessage(rect);
  request.set_page_size(page_size);
  return request;
}

class E2eNginxTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    direct_ = ScallopdProcess::Start(kReplicaArguments).release();
    std::vector<std::string> addresses, http_addresses;
    for (int r = 0; r < kReplicas; ++r) {
      if (!StartReplica(r, "127.0.0.1:0")) return;
      addresses.push_back(replicas_[r]->address());
      http_addresses.push_back(http_[r]);
    }
    nginx_ = NginxProcess::Start(SCALLOP_NGINX_CONFIG,
                                 {{"scallopd_grpc", addresses}, {"scallopd_http", http_addresses}})
                 .release();
  }
  static void TearDownTestSuite() {
    delete nginx_;
    delete direct_;
    for (ScallopdProcess*& replica : replicas_) delete replica;
  }
  void SetUp() override {
    ASSERT_NE(direct_, nullptr);
    for (ScallopdProcess* replica : replicas_) ASSERT_NE(replica, nullptr);
    ASSERT_NE(nginx_, nullptr);
  }

  // `listen` by value: it may be the address of the replica it replaces. The
  // HTTP port is the one replica r had, if it had one.
  static bool StartReplica(int r, const std::string listen) {
    delete replicas_[r];
    std::vector<std::string> arguments = kReplicaArguments;
    arguments.insert(arguments.end(),
                     {"--http-listen", http_[r].empty() ? "127.0.0.1:0" : http_[r]});
    replicas_[r] = ScallopdProcess::Start(arguments, listen).release();
    if (replicas_[r] == nullptr) return false;
    const std::string metrics = replicas_[r]->ReadStdoutLine(std::chrono::seconds(10));
    metrics_[r] = metrics.substr(metrics.rfind(' ') + 1);
    const std::string http = replicas_[r]->ReadStdoutLine(std::chrono::seconds(10));
    http_[r] = http.substr(http.rfind(' ') + 1);
    return true;
  }

  // Kills replica r at once (no drain, no grace), as a crash would.
  static void KillReplica(int r) {
    replicas_[r]->Signal(SIGKILL);
    EXPECT_EQ(replicas_[r]->WaitForExit(std::chrono::seconds(10)), -2 - SIGKILL);
  }

  // The replica with a call in flight, once one has (polled for 20 s); -1 if none.
  static int ReplicaInFlight() {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (std::chrono::steady_clock::now() < deadline) {
      for (int r = 0; r < kReplicas; ++r) {
        if (ScrapeMetrics(metrics_[r])["scallop_requests_in_flight"] > 0) return r;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return -1;
  }

  static double CallsServed(int r, const std::string& method) {
    double calls = 0;
    for (const auto& [key, value] : ScrapeMetrics(metrics_[r])) {
      if (key.rfind("scallop_requests_total{method=\"" + method + "\"", 0) == 0) calls += value;
    }
    return calls;
  }

  struct KilledCall {
    int victim = -1;  // the replica killed, -1 if the call never showed
    grpc::Status status;
    bool same_as_direct = false;
  };
  // A GetPoints of `rect` of "hills" (cold and slow on one thread: A1, so in
  // flight long enough to be caught) made through `client`; the replica
  // computing it is killed under it.
  static KilledCall KillReplicaUnderCall(client::ScallopClient& client, const Rect& rect) {
    const v1::GetPointsRequest slow = PointsRequest("hills", rect);
    PlanePoints expected, got;
    KilledCall killed;
    EXPECT_TRUE(direct_->Client().GetAllPoints(slow, expected).ok());
    std::thread call([&] { killed.status = client.GetAllPoints(slow, got); });
    killed.victim = ReplicaInFlight();
    if (killed.victim >= 0) KillReplica(killed.victim);
    call.join();
    killed.same_as_direct = got.ids == expected.ids && got.positions == expected.positions;
    return killed;
  }

  // dns:/// asks for the client's retry policy (service_config.h).
  static client::ScallopClient ThroughNginx() {
    return client::ScallopClient::Connect("dns:///" + nginx_->Address(kNginxGrpcPort));
  }

  static inline ScallopdProcess* direct_ = nullptr;
  static inline ScallopdProcess* replicas_[kReplicas] = {};
  static inline std::string metrics_[kReplicas];
  static inline std::string http_[kReplicas];  // --http-listen, kept across restarts
  static inline NginxProcess* nginx_ = nullptr;
};

// One unary call made directly and through `balanced`: both succeed, with
// the same bytes.
template <typename Request, typename Response>
void SameAnswer(client::ScallopClient& direct, client::ScallopClient& balanced,
                grpc::Status (client::ScallopClient::*call)(const Request&, Response&,
                                                            const client::CallOptions&),
                const Request& request, int round) {
  Response want, have;
  ASSERT_TRUE((direct.*call)(request, want, {}).ok()) << round;
  const grpc::Status status = (balanced.*call)(request, have, {});
  ASSERT_TRUE(status.ok()) << "round " << round << ": " << client::DescribeStatus(status);
  EXPECT_EQ(have.SerializeAsString(), want.SerializeAsString()) << round;
}

// Pages of one rectangle served by different replicas join up: the tokens
// cross replicas, and the whole equals the direct answer.
TEST_F(E2eNginxTest, PagesFromDifferentReplicasJoinUp) {
  client::ScallopClient nginx = ThroughNginx(), direct = direct_->Client();
  const size_t lines_before = ParseAccessLog(nginx_->ReadFile("scallop-grpc.log")).size();
  const v1::GetPointsRequest request = PointsRequest("coast", {-40.5, -30, 35, 42}, 97);
  PlanePoints expected, got;
  ASSERT_TRUE(direct.GetAllPoints(request, expected).ok());
  const grpc::Status status = nginx.GetAllPoints(request, got);
  ASSERT_TRUE(status.ok()) << client::DescribeStatus(status);
  ASSERT_GT(expected.ids.size(), 10 * 97u);
  EXPECT_EQ(got.ids, expected.ids);
  EXPECT_EQ(got.positions, expected.positions);

  // nginx writes a call's line when it ends: these are our pages, in order.
  const size_t pages = (expected.ids.size() + 96) / 97;
  const std::vector<AccessLine> lines = AccessLogOnceItHas(*nginx_, lines_before + pages);
  ASSERT_EQ(lines.size() - lines_before, pages);
  std::set<std::string> upstreams;
  for (size_t k = lines_before; k < lines.size(); ++k) {
    EXPECT_EQ(lines[k].method, "GetPoints");
    EXPECT_EQ(lines[k].status, 200);
    upstreams.insert(lines[k].upstream);
    if (k > lines_before) {
      EXPECT_NE(lines[k].upstream, lines[k - 1].upstream) << "page " << k - lines_before;
    }
  }
  EXPECT_EQ(upstreams.size(), size_t{kReplicas});
  for (int r = 0; r < kReplicas; ++r) {
    EXPECT_TRUE(upstreams.contains(replicas_[r]->address())) << replicas_[r]->address();
    EXPECT_GT(CallsServed(r, "GetPoints"), 0) << "replica " << r;
  }
}

// StreamPoints and Follow pass through nginx unchanged.
TEST_F(E2eNginxTest, StreamsAndFollowPassThrough) {
  client::ScallopClient nginx = ThroughNginx(), direct = direct_->Client();
  v1::StreamPointsRequest stream;
  stream.set_world_name("hills");
  *stream.mutable_rect() = RectToMessage({-60, -40, 50, 61.5});
  PlanePoints expected, got;
  ASSERT_TRUE(direct.GetAllPoints(PointsRequest("hills", {-60, -40, 50, 61.5}), expected).ok());
  const grpc::Status status = nginx.StreamAllPoints(stream, got);
  ASSERT_TRUE(status.ok()) << client::DescribeStatus(status);
  EXPECT_EQ(got.ids, expected.ids);
  EXPECT_EQ(got.positions, expected.positions);

  // The same walk followed directly and through nginx: the same messages.
  auto follow = [](const client::ScallopClient& client, std::vector<std::string>& messages) {
    client::FollowSession session(client, {.timeout = std::chrono::seconds(60)});
    for (int step = 0; step < 6; ++step) {
      v1::FollowRequest request;
      if (step == 0) request.set_world_name("coast");
      *request.mutable_viewport() = RectToMessage({step * 9.5, step * 3.0, step * 9.5 + 64, 48});
      request.set_keep_margin(8);
      const grpc::Status status = session.Update(
          request, [&](const v1::FollowResponse& r) { messages.push_back(r.SerializeAsString()); });
      if (!status.ok()) return status;
    }
    return session.Finish();
  };
  std::vector<std::string> followed_direct, followed_nginx;
  ASSERT_TRUE(follow(direct, followed_direct).ok());
  const grpc::Status followed = follow(nginx, followed_nginx);
  ASSERT_TRUE(followed.ok()) << client::DescribeStatus(followed);
  EXPECT_GT(followed_direct.size(), 20u);
  EXPECT_EQ(followed_nginx, followed_direct);
}

// A Nearest batch over 1 MiB: nginx's default client_max_body_size would
// refuse it (413, which gRPC reports as an error).
TEST_F(E2eNginxTest, LargeRequestsPass) {
  client::ScallopClient nginx = ThroughNginx(), direct = direct_->Client();
  v1::NearestRequest request;
  request.set_world_name("coast");
  for (int k = 0; k < 65536; ++k) {
    request.mutable_positions()->add_xs((k % 256) * 0.37);
    request.mutable_positions()->add_ys((k / 256) * 0.41);
  }
  ASSERT_GT(request.ByteSizeLong(), size_t{1} << 20);
  v1::NearestResponse expected, got;
  ASSERT_TRUE(direct.Nearest(request, expected).ok());
  const grpc::Status status = nginx.Nearest(request, got);
  ASSERT_TRUE(status.ok()) << client::DescribeStatus(status);
  EXPECT_EQ(got.SerializeAsString(), expected.SerializeAsString());
}

// How many client connections nginx saw for `calls` GetServerInfo calls made
// on one channel through the nginx at `address`.
size_t ConnectionsForCalls(const NginxProcess& nginx, int calls) {
  client::ScallopClient client = client::ScallopClient::Connect(nginx.Address(kNginxGrpcPort));
  const size_t before = ParseAccessLog(nginx.ReadFile("scallop-grpc.log")).size();
  for (int call = 0; call < calls; ++call) {
    v1::GetServerInfoResponse info;
    EXPECT_TRUE(client.GetServerInfo(info).ok()) << "call " << call;
  }
  std::vector<AccessLine> lines = AccessLogOnceItHas(nginx, before + static_cast<size_t>(calls));
  std::set<std::string> connections;
  for (size_t k = before; k < lines.size(); ++k) connections.insert(lines[k].connection);
  return connections.size();
}

// A gRPC client keeps one connection: past nginx's default keepalive_requests
// (1000) nginx would send GOAWAY and make it reconnect. With the shipped
// setting, 1,200 calls share one connection; the planted fault (the limit
// lowered to 100) is caught by the same count.
TEST_F(E2eNginxTest, ManyCallsShareOneConnection) {
  EXPECT_EQ(ConnectionsForCalls(*nginx_, 1200), 1u);

  std::ifstream in(SCALLOP_NGINX_CONFIG);
  std::stringstream text;
  text << in.rdbuf();
  const std::string planted_path = ::testing::TempDir() + "/nginx_planted_keepalive.conf";
  std::ofstream(planted_path) << std::regex_replace(
      text.str(), std::regex(R"((\n    keepalive_requests) \d+;)"), "$1 100;");
  std::vector<std::string> addresses;
  for (ScallopdProcess* replica : replicas_) addresses.push_back(replica->address());
  std::unique_ptr<NginxProcess> planted =
      NginxProcess::Start(planted_path, {{"scallopd_grpc", addresses}});
  ASSERT_NE(planted, nullptr);
  ASSERT_NE(planted->Config().find("keepalive_requests 100;"), std::string::npos);
  EXPECT_GE(ConnectionsForCalls(*planted, 1200), 12u);
}

// The shipped timeouts outlast the replicas' own (read from a replica with
// the default settings): scallopd, not nginx, ends an idle or stalled call.
TEST_F(E2eNginxTest, ProxyTimeoutsOutlastTheServers) {
  v1::GetServerInfoResponse info;
  ASSERT_TRUE(replicas_[0]->Client().GetServerInfo(info).ok());
  const v1::Limits& limits = info.limits();
  std::ifstream in(SCALLOP_NGINX_CONFIG);
  std::stringstream text;
  text << in.rdbuf();
  auto seconds = [&](const std::string& directive) {
    std::smatch match;
    const std::string config = text.str();
    if (!std::regex_search(config, match, std::regex("\n\\s*" + directive + R"( (\d+)s;)"))) {
      ADD_FAILURE() << directive << " not set in seconds";
      return 0.0;
    }
    return std::stod(match[1]);
  };
  for (const char* directive : {"grpc_read_timeout", "grpc_send_timeout", "client_body_timeout"}) {
    EXPECT_GT(seconds(directive), limits.follow_idle_seconds()) << directive;
    EXPECT_GT(seconds(directive), limits.stream_stall_seconds()) << directive;
  }
  EXPECT_GT(seconds("send_timeout"), limits.stream_stall_seconds());
  EXPECT_GT(seconds("send_timeout"), limits.follow_stall_seconds());
  EXPECT_GT(seconds("keepalive_timeout"), 60);
}

// A replica dies while it computes a call: nginx answers 502 (the call was
// sent, so nginx does not resend it), the client's retry policy sends it
// again, another replica answers. While it is down and once it is back, every
// unary call answers as the direct server does.
TEST_F(E2eNginxTest, UnaryCallsSurviveAReplicaKilledAndRestarted) {
  client::ScallopClient nginx = ThroughNginx(), direct = direct_->Client();
  const KilledCall killed = KillReplicaUnderCall(nginx, {2000, 2000, 2160, 2160});
  ASSERT_GE(killed.victim, 0) << "the slow call never showed in a replica's metrics";
  const int victim = killed.victim;
  const std::string victim_address = replicas_[victim]->address();
  ASSERT_TRUE(killed.status.ok()) << client::DescribeStatus(killed.status);
  EXPECT_TRUE(killed.same_as_direct);
  bool failed_on_victim = false;
  for (const AccessLine& line : ParseAccessLog(nginx_->ReadFile("scallop-grpc.log"))) {
    failed_on_victim |=
        line.status == 502 && line.upstream.find(victim_address) != std::string::npos;
  }
  EXPECT_TRUE(failed_on_victim) << "no 502 from " << victim_address << " in:\n"
                                << nginx_->ReadFile("scallop-grpc.log");

  // Every kind of idempotent call, while the victim is down, then back.
  auto every_call_agrees = [&](int round) {
    const Rect rect{-30.0 + round, 10, 25, 60.0 + round};
    PlanePoints want, have;
    ASSERT_TRUE(direct.GetAllPoints(PointsRequest("coast", rect, 211), want).ok());
    ASSERT_TRUE(nginx.GetAllPoints(PointsRequest("coast", rect, 211), have).ok()) << round;
    EXPECT_EQ(have.ids, want.ids);
    EXPECT_EQ(have.positions, want.positions);
    v1::NoiseGridRequest grid;
    grid.set_world_name("coast");
    grid.set_origin_x(rect.x0);
    grid.set_origin_y(rect.y0);
    grid.set_step(0.75);
    grid.set_width(40);
    grid.set_height(30);
    grid.set_channel(v1::NOISE_CHANNEL_F2_MINUS_F1);
    SameAnswer(direct, nginx, &client::ScallopClient::NoiseGrid, grid, round);
    v1::VerifyRequest verify;
    verify.set_world_name("hills");
    *verify.mutable_rect() = RectToMessage(rect);
    SameAnswer(direct, nginx, &client::ScallopClient::Verify, verify, round);
    v1::DescribeWorldRequest describe;
    describe.set_world_name("hills");
    SameAnswer(direct, nginx, &client::ScallopClient::DescribeWorld, describe, round);
  };
  for (int round = 0; round < 6; ++round) every_call_agrees(round);

  ASSERT_TRUE(StartReplica(victim, victim_address));
  // nginx takes a failed replica back after fail_timeout (5 s): keep calling
  // until the restarted one has answered (bounded), every answer checked.
  for (int round = 0; round < 400 && CallsServed(victim, "GetPoints") == 0; ++round) {
    every_call_agrees(round % 7);
    if (HasFatalFailure()) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  }
  EXPECT_GT(CallsServed(victim, "GetPoints"), 0) << "the restarted replica was never used";
}

// The client library alone, no proxy: Connect("ipv4:A,B,C") balances
// round_robin over the replicas and retries a call whose replica dies under
// it. The planted fault, a channel without the retry policy, fails instead.
// And dns:/// targets resolve.
TEST_F(E2eNginxTest, ClientLibraryBalancesAndRetriesWithoutAProxy) {
  std::string targets = "ipv4:";
  double before[kReplicas];
  for (int r = 0; r < kReplicas; ++r) {
    targets += (r ? "," : "") + replicas_[r]->address();
    before[r] = CallsServed(r, "DescribeWorld");
  }
  client::ScallopClient balanced = client::ScallopClient::Connect(targets);
  v1::DescribeWorldRequest describe;
  describe.set_world_name("coast");
  // round_robin sends only to connected replicas: call until all have
  // answered (bounded), as a busy machine may connect one late.
  for (int call = 0; call < 300; ++call) {
    v1::DescribeWorldResponse world;
    ASSERT_TRUE(balanced.DescribeWorld(describe, world).ok());
    if (call % 30 == 29 && CallsServed(0, "DescribeWorld") > before[0] &&
        CallsServed(1, "DescribeWorld") > before[1] &&
        CallsServed(2, "DescribeWorld") > before[2]) {
      break;
    }
  }
  for (int r = 0; r < kReplicas; ++r) {
    EXPECT_GT(CallsServed(r, "DescribeWorld"), before[r]) << "replica " << r;
  }

  const KilledCall killed = KillReplicaUnderCall(balanced, {-3000, -3000, -2840, -2840});
  ASSERT_GE(killed.victim, 0) << "the slow call never showed in a replica's metrics";
  EXPECT_TRUE(killed.status.ok()) << client::DescribeStatus(killed.status);
  EXPECT_TRUE(killed.same_as_direct);
  ASSERT_TRUE(StartReplica(killed.victim, replicas_[killed.victim]->address()));

  grpc::ChannelArguments arguments;
  arguments.SetLoadBalancingPolicyName("round_robin");
  client::ScallopClient without_retries(
      grpc::CreateCustomChannel(targets, grpc::InsecureChannelCredentials(), arguments));
  const KilledCall planted = KillReplicaUnderCall(without_retries, {3000, 3000, 3160, 3160});
  ASSERT_GE(planted.victim, 0);
  EXPECT_EQ(planted.status.error_code(), grpc::StatusCode::UNAVAILABLE)
      << client::DescribeStatus(planted.status);
  ASSERT_TRUE(StartReplica(planted.victim, replicas_[planted.victim]->address()));

  const std::string address = replicas_[0]->address();
  client::ScallopClient named =
      client::ScallopClient::Connect("dns:///localhost:" + address.substr(address.rfind(':') + 1));
  v1::GetServerInfoResponse info;
  const grpc::Status status = named.GetServerInfo(info);
  ASSERT_TRUE(status.ok()) << client::DescribeStatus(status);
  EXPECT_EQ(info.limits().stream_stall_seconds(), 10);
}

// A stream whose replica dies ends with a status (not a hang, not OK), and
// streams of StreamRemainder's rectangles continue it: no region missing,
// none twice, the whole equal to the direct answer.
TEST_F(E2eNginxTest, BrokenStreamResumesWhereItStopped) {
  client::ScallopClient nginx = ThroughNginx(), direct = direct_->Client();
  const Rect rect{-307.25, -211, 190, 286.5};
  PlanePoints expected;
  ASSERT_TRUE(direct.GetAllPoints(PointsRequest("coast", rect), expected).ok());

  std::vector<RegionKey> regions;  // of every chunk received, in order
  PlanePoints got;
  int victim = -1;
  auto take = [&](const v1::PointsChunk& chunk) {
    regions.push_back({chunk.region_i(), chunk.region_j()});
    EXPECT_TRUE(ReadPoints(chunk.points(), got).ok());
  };
  v1::StreamPointsRequest stream;
  stream.set_world_name("coast");
  *stream.mutable_rect() = RectToMessage(rect);
  const grpc::Status broken =
      nginx.StreamPoints(stream,
                         [&](const v1::PointsChunk& chunk) {
                           take(chunk);
                           if (regions.size() == 5) {  // mid-stream: the replica waits on us
                             victim = ReplicaInFlight();
                             if (victim >= 0) KillReplica(victim);
                           }
                           return true;
                         },
                         {.timeout = std::chrono::seconds(60)});
  ASSERT_GE(victim, 0) << "the stream never showed in a replica's metrics";
  ASSERT_FALSE(broken.ok()) << "the stream ended normally after " << regions.size() << " chunks";
  EXPECT_NE(broken.error_code(), grpc::StatusCode::DEADLINE_EXCEEDED)
      << "the break was noticed only at the deadline";
  std::cerr << "broken stream: " << client::DescribeStatus(broken) << " after " << regions.size()
            << " chunks\n";
  ASSERT_LT(got.ids.size(), expected.ids.size());

  for (const Rect& rest : client::StreamRemainder(rect, regions.back(), 1.0)) {
    *stream.mutable_rect() = RectToMessage(rest);
    const grpc::Status status = nginx.StreamPoints(stream, [&](const v1::PointsChunk& chunk) {
      take(chunk);
      return true;
    });
    ASSERT_TRUE(status.ok()) << client::DescribeStatus(status);
  }
  for (size_t k = 1; k < regions.size(); ++k) {
    EXPECT_LT(std::tie(regions[k - 1].j, regions[k - 1].i), std::tie(regions[k].j, regions[k].i))
        << "chunk " << k << " repeats or goes back";
  }
  EXPECT_EQ(got.ids, expected.ids);
  EXPECT_EQ(got.positions, expected.positions);
  ASSERT_TRUE(StartReplica(victim, replicas_[victim]->address()));
}

// A stream's points, ids and layers, as received.
bool SamePoints(const PlanePoints& got, const PlanePoints& expected) {
  return got.ids == expected.ids && got.positions == expected.positions &&
         got.layers == expected.layers;
}

// A layered world's stream (trees, bushes, rocks) whose replica dies mid-layer, unfiltered and
// with the filter {rocks, trees}: StreamResumeRequests' streams, on another replica, continue
// it, and the whole equals an unbroken stream's ids, positions and layers. Resumes planted from
// the same break, one repeating the last region and one dropping the filter for the later
// layers, are caught by the same comparison. The calls go to the replicas directly (the break
// is then UNAVAILABLE): nginx, which marks a replica it sees fail as down for 5 s, would see
// two more failures next to the tests' others and find every replica down (502).
TEST_F(E2eNginxTest, BrokenLayeredStreamResumesWhereItStopped) {
  client::ScallopClient direct = direct_->Client();
  // Break the stream of a forest of seed `seed` on replica `victim` after `chunks` chunks, which
  // must leave it in layer `layer`. Each case has its own seed, so every replica is cold for it: a
  // stream waits on the generation of its next regions, so none of them is on the way to the client
  // when the replica dies (with a warm replica, chunks written before the kill still arrive).
  auto break_and_resume = [&](uint64_t seed, std::vector<std::string> filter, int victim,
                              size_t chunks, uint32_t layer) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    WorldSpec forest{.seed = seed};
    forest.layers = {{.name = "trees", .min_distance = 8},
                     {.name = "bushes", .min_distance = 3},
                     {.name = "rocks", .min_distance = 1.5}};
    v1::DescribeWorldRequest describe;
    *describe.mutable_world() = WorldToMessage(forest);
    v1::DescribeWorldResponse world;
    ASSERT_TRUE(direct.DescribeWorld(describe, world).ok());
    ASSERT_EQ(world.layers_size(), 3);
    v1::StreamPointsRequest stream;
    *stream.mutable_world() = describe.world();
    *stream.mutable_rect() = RectToMessage({-150.5, -120, 170, 140.25});
    for (const std::string& name : filter) stream.add_layers(name);
    PlanePoints expected;
    ASSERT_TRUE(direct.StreamAllPoints(stream, expected).ok());
    ASSERT_FALSE(expected.layers.empty());

    PlanePoints got;
    std::optional<client::StreamPosition> last;
    client::ScallopClient replica = replicas_[victim]->Client();
    client::ScallopClient other = replicas_[(victim + 1) % kReplicas]->Client();
    const grpc::Status broken =
        replica.StreamPoints(stream,
                             [&](const v1::PointsChunk& chunk) {
                               last = client::StreamPosition::Of(chunk);
                               EXPECT_TRUE(ReadPoints(chunk.points(), got).ok());
                               if (--chunks == 0) KillReplica(victim);  // it waits on us
                               return true;
                             },
                             {.timeout = std::chrono::seconds(60)});
    ASSERT_FALSE(broken.ok()) << "the stream ended normally";
    EXPECT_NE(broken.error_code(), grpc::StatusCode::DEADLINE_EXCEEDED);
    ASSERT_TRUE(last.has_value());
    std::cerr << "broken layered stream: " << client::DescribeStatus(broken) << " in layer "
              << last->layer << ", region (" << last->region.i << ", " << last->region.j
              << "), after " << got.ids.size() << " of " << expected.ids.size() << " points\n";
    EXPECT_EQ(last->layer, layer);
    ASSERT_LT(got.ids.size(), expected.ids.size());

    // The rest from requests, on another replica.
    auto resumed = [&](const std::vector<v1::StreamPointsRequest>& requests) {
      PlanePoints whole = got;
      for (const v1::StreamPointsRequest& rest : requests) {
        const grpc::Status status = other.StreamAllPoints(rest, whole);
        EXPECT_TRUE(status.ok()) << client::DescribeStatus(status);
      }
      return whole;
    };
    StatusOr<std::vector<v1::StreamPointsRequest>> requests =
        client::StreamResumeRequests(stream, world, last);
    ASSERT_TRUE(requests.ok()) << requests.status().message();
    EXPECT_TRUE(SamePoints(resumed(*requests), expected));

    std::vector<v1::StreamPointsRequest> repeats_last = *requests;
    v1::StreamPointsRequest last_region = stream;
    const double side = world.layers(static_cast<int>(last->layer)).region_side();
    const Rect rect = RectFromMessage(stream.rect());
    *last_region.mutable_rect() = RectToMessage({std::max(rect.x0, last->region.i * side),
                                                 std::max(rect.y0, last->region.j * side),
                                                 std::min(rect.x1, (last->region.i + 1) * side),
                                                 std::min(rect.y1, (last->region.j + 1) * side)});
    last_region.clear_layers();
    last_region.add_layers(world.layers(static_cast<int>(last->layer)).name());
    repeats_last.insert(repeats_last.begin(), last_region);
    EXPECT_FALSE(SamePoints(resumed(repeats_last), expected)) << "a repeated region passed";
    v1::StreamPointsRequest unfiltered = stream;
    unfiltered.clear_layers();
    std::vector<v1::StreamPointsRequest> forgets_filter =
        *client::StreamResumeRequests(unfiltered, world, last);
    if (!filter.empty()) {
      EXPECT_FALSE(SamePoints(resumed(forgets_filter), expected)) << "a lost filter passed";
    }
    ASSERT_TRUE(StartReplica(victim, replicas_[victim]->address()));
  };
  break_and_resume(7, {}, 0, 16, 1);                 // the trees' 12 regions, then mid-bushes
  break_and_resume(8, {"rocks", "trees"}, 1, 4, 0);  // in trees, bushes skipped, then rocks
}

// A Follow call whose replica dies ends with a status; a new call that names
// the regions held whole gets the rest of the view and none of them again.
TEST_F(E2eNginxTest, BrokenFollowResumesWithHeldRegions) {
  client::ScallopClient nginx = ThroughNginx(), direct = direct_->Client();
  client::FollowedPoints held;
  int victim = -1;
  {
    client::FollowSession session(nginx, {.timeout = std::chrono::seconds(60)});
    v1::FollowRequest first;
    first.set_world_name("coast");
    *first.mutable_viewport() = RectToMessage({0, 0, 64, 64});  // regions (0..3, 0..3), whole
    ASSERT_TRUE(session.Update(first, [&](const v1::FollowResponse& r) { held.Apply(r); }).ok());
    victim = ReplicaInFlight();  // the open call holds a stream slot
    ASSERT_GE(victim, 0);
    KillReplica(victim);
    v1::FollowRequest next;
    *next.mutable_viewport() = RectToMessage({16, 0, 80, 64});
    const grpc::Status broken = session.Update(next, [](const v1::FollowResponse&) {});
    ASSERT_FALSE(broken.ok());
    EXPECT_NE(broken.error_code(), grpc::StatusCode::DEADLINE_EXCEEDED);
    std::cerr << "broken follow: " << client::DescribeStatus(broken) << '\n';
  }
  ASSERT_EQ(held.Regions().size(), 16u);

  client::FollowSession resumed(nginx, {.timeout = std::chrono::seconds(60)});
  v1::FollowRequest request;
  request.set_world_name("coast");
  *request.mutable_viewport() = RectToMessage({16, 0, 80, 64});
  for (const RegionKey& key : held.Regions()) {
    v1::RegionKey& region = *request.add_held_regions();
    region.set_i(key.i);
    region.set_j(key.j);
  }
  std::set<uint64_t> have;
  for (const RegionKey& key : held.Regions()) {
    for (uint64_t id : held.PointsOf(key).ids) {
      if (key.i >= 1) have.insert(id);  // still in view
    }
  }
  const grpc::Status status = resumed.Update(request, [&](const v1::FollowResponse& response) {
    for (uint64_t id : response.chunk().points().ids()) {
      EXPECT_TRUE(have.insert(id).second) << "point " << id << " came again";
    }
  });
  ASSERT_TRUE(status.ok()) << client::DescribeStatus(status);
  PlanePoints expected;
  ASSERT_TRUE(direct.GetAllPoints(PointsRequest("coast", {16, 0, 80, 64}), expected).ok());
  EXPECT_EQ(have, std::set<uint64_t>(expected.ids.begin(), expected.ids.end()));
  ASSERT_TRUE(StartReplica(victim, replicas_[victim]->address()));
}

}  // namespace
}  // namespace scallop::testing

namespace scallop::testing {
namespace {

namespace http = boost::beast::http;

// What a client can see of a tile: status, bytes and the caching headers.
std::string Visible(const HttpAnswer& answer) {
  auto header = [&](const char* name) {
    const auto found = answer.headers.find(name);
    return found == answer.headers.end() ? std::string("(none)") : found->second;
  };
  return std::to_string(answer.status) + " etag=" + header("etag") +
         " cache-control=" + header("cache-control") + " content-type=" + answer.content_type +
         " bytes=" + std::to_string(answer.body.size()) + ":" + answer.body;
}

std::string CacheStatus(const HttpAnswer& answer) {
  const auto found = answer.headers.find("x-cache-status");
  return found == answer.headers.end() ? "(none)" : found->second;
}

// The second request for a tile is a cache hit that no replica sees, with
// the bytes and ETag a replica gives directly; If-None-Match gets 304 from
// the cache. Errors are not stored (the planted fault: an error cached would
// show HIT the second time).
TEST_F(E2eNginxTest, SecondRequestForATileIsACacheHit) {
  const std::string nginx = nginx_->Address(kNginxHttpPort);
  for (const char* target :
       {"/v1/worlds/coast/tiles/3/-2.bin?level=1", "/v1/worlds/hills/tiles/-7/5.json",
        "/v1/worlds/coast/tiles/0/1.png"}) {
    const HttpAnswer direct = Fetch(http_[0], http::verb::get, target);
    ASSERT_EQ(direct.status, 200) << target << ": " << direct.body;
    ASSERT_FALSE(direct.headers.at("etag").empty());
    const HttpAnswer first = Fetch(nginx, http::verb::get, target);
    EXPECT_EQ(CacheStatus(first), "MISS") << target;
    double tiles_served = 0;
    for (int r = 0; r < kReplicas; ++r) tiles_served += CallsServed(r, "HttpTile");
    const HttpAnswer second = Fetch(nginx, http::verb::get, target);
    EXPECT_EQ(CacheStatus(second), "HIT") << target;
    EXPECT_EQ(Visible(first), Visible(direct)) << target;
    EXPECT_EQ(Visible(second), Visible(direct)) << target;
    double tiles_served_after = 0;
    for (int r = 0; r < kReplicas; ++r) tiles_served_after += CallsServed(r, "HttpTile");
    EXPECT_EQ(tiles_served_after, tiles_served) << target << ": a hit reached a replica";

    const HttpAnswer revalidated =
        Fetch(nginx, http::verb::get, target, {{"If-None-Match", direct.headers.at("etag")}});
    EXPECT_EQ(revalidated.status, 304) << target;
    EXPECT_EQ(revalidated.headers.at("etag"), direct.headers.at("etag"));
    EXPECT_EQ(CacheStatus(revalidated), "HIT");
  }
  for (int attempt = 0; attempt < 2; ++attempt) {
    const HttpAnswer unknown = Fetch(nginx, http::verb::get, "/v1/worlds/nowhere/tiles/0/0");
    EXPECT_EQ(unknown.status, 404);
    EXPECT_EQ(CacheStatus(unknown), "MISS") << "an error was stored";
  }
}

// Every replica killed, then restarted: a client sees the same status, bytes
// and caching headers for every tile, cached or not, and cached tiles are
// served even while no replica runs.
TEST_F(E2eNginxTest, RestartingEveryReplicaChangesNothingAClientSees) {
  const std::string nginx = nginx_->Address(kNginxHttpPort);
  const std::vector<std::string> cached = {"/v1/worlds/coast/tiles/11/12.bin?level=2",
                                           "/v1/worlds/hills/tiles/-3/-4.json",
                                           "/v1/worlds/coast/tiles/5/5.png?level=1"};
  const std::vector<std::string> uncached = {"/v1/worlds/coast/tiles/-20/9.json?level=1",
                                             "/v1/worlds/hills/tiles/40/-41.bin"};
  std::map<std::string, std::string> before;
  for (const std::string& target : cached) {
    before[target] = Visible(Fetch(nginx, http::verb::get, target));
    ASSERT_EQ(before[target].substr(0, 4), "200 ") << target;
  }
  for (const std::string& target : uncached) {
    before[target] = Visible(Fetch(http_[1], http::verb::get, target));  // not through nginx
    ASSERT_EQ(before[target].substr(0, 4), "200 ") << target;
  }

  for (int r = 0; r < kReplicas; ++r) KillReplica(r);
  for (const std::string& target : cached) {
    const HttpAnswer answer = Fetch(nginx, http::verb::get, target);
    EXPECT_EQ(Visible(answer), before[target]) << target << " with every replica down";
    EXPECT_EQ(CacheStatus(answer), "HIT") << target;
  }
  for (int r = 0; r < kReplicas; ++r) ASSERT_TRUE(StartReplica(r, replicas_[r]->address()));

  for (const std::string& target : cached) {
    EXPECT_EQ(Visible(Fetch(nginx, http::verb::get, target)), before[target]) << target;
  }
  for (const std::string& target : uncached) {
    const HttpAnswer answer = Fetch(nginx, http::verb::get, target);
    EXPECT_EQ(CacheStatus(answer), "MISS") << target;
    EXPECT_EQ(Visible(answer), before[target]) << target << " from a restarted replica";
  }
  // And gRPC through the same nginx still answers as the direct server.
  PlanePoints want, have;
  ASSERT_TRUE(
      direct_->Client().GetAllPoints(PointsRequest("coast", {1, 2, 30, 40}, 50), want).ok());
  const grpc::Status status =
      ThroughNginx().GetAllPoints(PointsRequest("coast", {1, 2, 30, 40}, 50), have);
  ASSERT_TRUE(status.ok()) << client::DescribeStatus(status);
  EXPECT_EQ(have.ids, want.ids);
}

// NginxProcess gives every configured port a loopback port of its own, and
// blocks that share a configured port share it. A configuration of many
// listens (which, when ports were picked and released one at a time, now and
// then gave two of them one port: nginx then answers both from the first
// block) answers each block's own text on its own address.
TEST(NginxProcessTest, EveryConfiguredPortListensApart) {
  constexpr int kListens = 256;
  std::ostringstream config;
  for (int k = 0; k < kListens; ++k) {
    config << "server {\n    listen " << 9000 + k << ";\n    return 200 \"block " << k
           << "\";\n}\n";
  }
  config << "server {\n    listen 9000;\n    server_name twin;\n    return 200 \"twin\";\n}\n";
  const std::string path = ::testing::TempDir() + "/nginx_many_listens.conf";
  std::ofstream(path) << config.str();
  const std::unique_ptr<NginxProcess> nginx = NginxProcess::Start(path, {});
  ASSERT_NE(nginx, nullptr);
  std::set<std::string> addresses;
  for (int k = 0; k < kListens; ++k) {
    const std::string address = nginx->Address(9000 + k);
    addresses.insert(address);
    EXPECT_EQ(Fetch(address, http::verb::get, "/").body, "block " + std::to_string(k)) << address;
  }
  EXPECT_EQ(addresses.size(), static_cast<size_t>(kListens));
  EXPECT_EQ(Fetch(nginx->Address(9000), http::verb::get, "/", {{"Host", "twin"}}).body, "twin");
}

}  // namespace
}  // namespace scallop::testing
