// End to end (issue 20, item 5): with a 256-file limit, 300 idle connections
// to /metrics neither take the gRPC port down nor end the metrics listener:
// its connections are capped, and it keeps accepting after errors. The same
// for the HTTP tiles' listener (issue 21), which is the same class.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <unistd.h>

#include <fstream>
#include <thread>
#include <vector>

#include "tests/e2e/metrics_scrape.h"
#include "tests/e2e/scallopd_process.h"

namespace scallop::testing {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

// scallopd started with a soft limit of `files` descriptors (the child
// inherits it; this process gets its own limit back at once).
std::unique_ptr<ScallopdProcess> StartWithFileLimit(rlim_t files,
                                                    const std::vector<std::string>& arguments) {
  rlimit original{};
  getrlimit(RLIMIT_NOFILE, &original);
  rlimit lowered = original;
  lowered.rlim_cur = files;
  setrlimit(RLIMIT_NOFILE, &lowered);
  std::unique_ptr<ScallopdProcess> server = ScallopdProcess::Start(arguments);
  setrlimit(RLIMIT_NOFILE, &original);
  return server;
}

// A connected TCP socket to HOST:PORT (IPv4), or -1.
int ConnectTo(const std::string& host_port) {
  const size_t colon = host_port.rfind(':');
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(std::stoi(host_port.substr(colon + 1))));
  inet_pton(AF_INET, host_port.substr(0, colon).c_str(), &address.sin_addr);
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  if (fd >= 0 && connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
    close(fd);
    return -1;
  }
  return fd;
}

// An HTTP listener of scallopd: its flag, the setting that caps its
// connections, the name its log lines start with, and a path it answers.
struct Listener {
  const char* flag;
  const char* cap_setting;
  const char* log_name;
  const char* path;
};
const Listener kMetrics{"--metrics-listen", "max_metrics_connections", "metrics", "/metrics"};
const Listener kTiles{"--http-listen", "max_http_connections", "http",
                      "/v1/worlds/default/tiles/0/0.bin"};

// True once `path` answers 200 (each try bounded), or false after `timeout`.
bool ScrapeSucceedsWithin(const std::string& host_port, const char* path, milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    try {
      if (Fetch(host_port, boost::beast::http::verb::get, path, seconds(2)).status == 200) {
        return true;
      }
    } catch (const std::exception&) {
      // Closed (over the cap) or not answered yet: try again.
    }
    std::this_thread::sleep_for(milliseconds(50));
  }
  return false;
}

// Holds 300 idle connections to `listener` of a server limited to 256
// files, its cap set to `cap`, checks gRPC while they are held (when
// `grpc_must_serve`), closes them, and expects requests to be answered again.
void HoldIdleConnections(const Listener& listener, int cap, bool grpc_must_serve) {
  const std::string config = ::testing::TempDir() + "e2e_listener_" + listener.log_name + ".yaml";
  std::ofstream(config) << listener.cap_setting << ": " << cap << "\n";
  auto server = StartWithFileLimit(256, {"--config", config, listener.flag, "127.0.0.1:0"});
  std::remove(config.c_str());
  ASSERT_NE(server, nullptr);
  const std::string line = server->ReadStdoutLine(seconds(10));
  const std::string metrics_address = line.substr(line.rfind(' ') + 1);
  ASSERT_TRUE(ScrapeSucceedsWithin(metrics_address, listener.path, seconds(10)));

  std::vector<int> idle;
  for (int k = 0; k < 300; ++k) {
    const int fd = ConnectTo(metrics_address);
    if (fd >= 0) idle.push_back(fd);
  }
  EXPECT_EQ(idle.size(), 300u);
  if (grpc_must_serve) {
    v1::GetServerInfoResponse info;
    const grpc::Status status = server->Client().GetServerInfo(info, {.timeout = seconds(10)});
    EXPECT_TRUE(status.ok()) << client::DescribeStatus(status);
  }
  if (!grpc_must_serve) {
    // The path under test is taken while they are held: an accept fails for
    // want of files.
    EXPECT_NE(server->WaitForLog(std::string(listener.log_name) + ": accept failed", seconds(20))
                  .find("Too many open files"),
              std::string::npos);
  }
  for (const int fd : idle) close(fd);
  // The event: requests are answered again.
  EXPECT_TRUE(ScrapeSucceedsWithin(metrics_address, listener.path, seconds(20))) << server->Log();
}

// The default cap (16): the listener never holds more than that, so the
// process keeps descriptors for gRPC while the connections are held.
TEST(E2eMetricsListenerTest, CappedConnectionsLeaveDescriptorsForGrpc) {
  HoldIdleConnections(kMetrics, 16, /*grpc_must_serve=*/true);
}
TEST(E2eMetricsListenerTest, CappedTileConnectionsLeaveDescriptorsForGrpc) {
  HoldIdleConnections(kTiles, 16, /*grpc_must_serve=*/true);
}

// A cap above the file limit: accept runs out of descriptors (EMFILE), and
// the listener must resume once they come back. The old one stopped for good.
TEST(E2eMetricsListenerTest, AcceptingResumesAfterRunningOutOfDescriptors) {
  HoldIdleConnections(kMetrics, 1024, /*grpc_must_serve=*/false);
}
TEST(E2eMetricsListenerTest, TileAcceptingResumesAfterRunningOutOfDescriptors) {
  HoldIdleConnections(kTiles, 1024, /*grpc_must_serve=*/false);
}

}  // namespace
}  // namespace scallop::testing
