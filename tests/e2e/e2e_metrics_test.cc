// End to end: scallopd --metrics-listen serves Prometheus text at /metrics
// whose counters agree with the calls a client made and with what it got
// back, and refuses other paths, other methods and a bad listen address.
#include <gtest/gtest.h>

#include <sstream>

#include "tests/e2e/metrics_scrape.h"
#include "tests/e2e/scallopd_process.h"
#include "tests/test_worlds.h"
#include "world_messages.h"

namespace scallop::testing {
namespace {

namespace http = boost::beast::http;

class E2eMetricsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    server_ = ScallopdProcess::Start({"--metrics-listen", "127.0.0.1:0", "--cache-megabytes", "1"});
    ASSERT_NE(server_, nullptr);
    const std::string line = server_->ReadStdoutLine(std::chrono::seconds(10));
    const std::string prefix = "scallopd metrics on ";
    ASSERT_EQ(line.rfind(prefix, 0), 0u) << line;
    metrics_address_ = line.substr(prefix.size());
  }

  std::map<std::string, double> Scrape() {
    const HttpAnswer answer = Fetch(metrics_address_, http::verb::get, "/metrics");
    EXPECT_EQ(answer.status, 200);
    EXPECT_EQ(answer.content_type, "text/plain; version=0.0.4; charset=utf-8");
    return ParseExposition(answer.body);
  }

  std::unique_ptr<ScallopdProcess> server_;
  std::string metrics_address_;
};

v1::GetPointsRequest PointsRequest(const Rect& rect) {
  v1::GetPointsRequest request;
  *request.mutable_world() = WorldToMessage(ValidWorld({.seed = 5}));
  *request.mutable_rect() = RectToMessage(rect);
  return request;
}

TEST_F(E2eMetricsTest, CountersAgreeWithTheCallsMade) {
  client::ScallopClient client = server_->Client();
  int64_t points_received = 0;
  const std::vector<Rect> rects{{0, 0, 40, 40}, {100, 0, 130, 20}, {0, 0, 40, 40}};
  for (const Rect& rect : rects) {
    v1::GetPointsResponse response;
    ASSERT_TRUE(client.GetPoints(PointsRequest(rect), response).ok());
    points_received += response.points().ids_size();
  }
  v1::GetPointsResponse ignored;
  const grpc::Status inverted = client.GetPoints(PointsRequest({10, 0, 0, 10}), ignored);
  ASSERT_EQ(inverted.error_code(), grpc::StatusCode::INVALID_ARGUMENT);

  std::map<std::string, double> metrics = Scrape();
  EXPECT_EQ(metrics["scallop_requests_total{method=\"GetPoints\",code=\"OK\"}"], 3);
  EXPECT_EQ(metrics["scallop_requests_total{method=\"GetPoints\",code=\"INVALID_ARGUMENT\"}"], 1);
  EXPECT_EQ(metrics["scallop_points_served_total{method=\"GetPoints\"}"], points_received);
  // Histogram: cumulative buckets, +Inf equal to the count of calls.
  const std::string bucket = "scallop_request_duration_seconds_bucket{method=\"GetPoints\",le=\"";
  double previous = 0;
  for (const double le : {0.0005, 0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1}) {
    std::ostringstream key;
    key << bucket << le << "\"}";
    ASSERT_TRUE(metrics.contains(key.str())) << key.str();
    EXPECT_GE(metrics[key.str()], previous);
    previous = metrics[key.str()];
  }
  EXPECT_EQ(metrics[bucket + "+Inf\"}"], 4);
  EXPECT_EQ(metrics["scallop_request_duration_seconds_count{method=\"GetPoints\"}"], 4);
  EXPECT_GT(metrics["scallop_request_duration_seconds_sum{method=\"GetPoints\"}"], 0);
  // The third call repeats the first: its regions are hits, none generated anew.
  EXPECT_GT(metrics["scallop_cache_misses_total"], 0);
  EXPECT_EQ(metrics["scallop_regions_generated_total"], metrics["scallop_cache_misses_total"]);
  EXPECT_GT(metrics["scallop_cache_hits_total"], 0);
  EXPECT_EQ(metrics["scallop_cache_budget_bytes"], 1 << 20);
  EXPECT_LE(metrics["scallop_cache_bytes"], metrics["scallop_cache_budget_bytes"]);
  EXPECT_EQ(metrics["scallop_requests_in_flight"], 0);

  // A repeat of a cached rectangle adds hits and no misses.
  const double misses = metrics["scallop_cache_misses_total"];
  const double hits = metrics["scallop_cache_hits_total"];
  ASSERT_TRUE(client.GetPoints(PointsRequest(rects[0]), ignored).ok());
  metrics = Scrape();
  EXPECT_EQ(metrics["scallop_cache_misses_total"], misses);
  EXPECT_GT(metrics["scallop_cache_hits_total"], hits);
  EXPECT_EQ(metrics["scallop_requests_total{method=\"GetPoints\",code=\"OK\"}"], 4);
}

TEST_F(E2eMetricsTest, OtherPathsAndMethodsAreRefused) {
  EXPECT_EQ(Fetch(metrics_address_, http::verb::get, "/").status, 404);
  EXPECT_EQ(Fetch(metrics_address_, http::verb::get, "/metricsx").status, 404);
  EXPECT_EQ(Fetch(metrics_address_, http::verb::post, "/metrics").status, 405);
  const HttpAnswer head = Fetch(metrics_address_, http::verb::head, "/metrics");
  EXPECT_EQ(head.status, 200);
  EXPECT_EQ(head.body, "");
}

TEST(E2eMetricsFlagTest, BadListenAddressIsRefusedByName) {
  for (const char* bad : {"nonsense", "127.0.0.1:99999", "not-an-ip:0"}) {
    auto server = ScallopdProcess::Start({"--metrics-listen", bad});
    EXPECT_EQ(server, nullptr) << bad;
  }
}

}  // namespace
}  // namespace scallop::testing
