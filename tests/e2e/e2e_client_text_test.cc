// End to end (issue 20, item 4): text a client sends (world_name) comes back
// in messages and goes to the log escaped and cut short: no forged log lines,
// no megabytes of log, and a long name is NOT_FOUND like any unknown name.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "tests/e2e/scallopd_process.h"
#include "world_messages.h"

namespace scallop::testing {
namespace {

using namespace std::string_literals;

grpc::Status GetPointsOfWorld(client::ScallopClient& client, const std::string& world_name) {
  v1::GetPointsRequest request;
  request.set_world_name(world_name);
  *request.mutable_rect() = RectToMessage({0, 0, 5, 5});
  v1::GetPointsResponse response;
  return client.GetPoints(request, response);
}

bool Printable(const std::string& text) {
  for (const char c : text) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return false;
  }
  return true;
}

TEST(E2eClientTextTest, ControlBytesAreEscapedInMessagesAndLog) {
  auto server = ScallopdProcess::Start({});
  ASSERT_NE(server, nullptr);
  client::ScallopClient client = server->Client();
  // A NUL and a newline, then what would pass for a log line of its own.
  const std::string forged = "x\0y\n[2026-01-01 00:00:00.000] [scallopd] [info] FORGED code=OK"s;
  const grpc::Status status = GetPointsOfWorld(client, forged);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::NOT_FOUND);
  EXPECT_TRUE(Printable(status.error_message())) << status.error_message();
  EXPECT_NE(status.error_message().find("x\\x00y\\x0a[2026"), std::string::npos)
      << status.error_message();
  // The call's log line is written when it ends: wait for it.
  const std::string log = server->WaitForLog("NOT_FOUND", std::chrono::seconds(10));
  std::istringstream lines(log);
  for (std::string line; std::getline(lines, line);) {
    EXPECT_NE(line.rfind("[2026-01-01", 0), 0u) << "a forged line: " << line;
  }
}

TEST(E2eClientTextTest, ALongNameIsNotFoundAndCutShort) {
  auto server = ScallopdProcess::Start({});
  ASSERT_NE(server, nullptr);
  client::ScallopClient client = server->Client();
  const size_t log_before = server->Log().size();
  // 1 MiB: over the 8 KB of trailers gRPC allows if echoed whole.
  const std::string name(size_t{1} << 20, 'w');
  const grpc::Status status = GetPointsOfWorld(client, name);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::NOT_FOUND) << client::DescribeStatus(status);
  EXPECT_LT(status.error_message().size(), 1024u);
  EXPECT_NE(status.error_message().find("(1048576 bytes)"), std::string::npos)
      << status.error_message();
  const std::string log = server->WaitForLog("NOT_FOUND", std::chrono::seconds(10));
  EXPECT_NE(log.find("NOT_FOUND"), std::string::npos);
  EXPECT_LT(log.size() - log_before, 4096u) << "the name went to the log whole";
}

}  // namespace
}  // namespace scallop::testing
