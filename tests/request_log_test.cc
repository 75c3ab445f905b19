// The access log: a call's line holds the fields docs/deploy.md promises
// (method, world, rectangle, points, milliseconds, code, and the message of a
// failed call), at the levels it promises; and the batching sink scallopd
// writes it through gives the descriptor exactly the lines spdlog's own
// sinks would, only later: when full, on flush (warnings flush at once) and
// at its end.
#include "server/request_log.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include "server/buffered_log_sink.h"
#include "server/world_registry.h"
#include "world_messages.h"

namespace scallop::server {
namespace {

// The default logger replaced by one writing to `out` at `level`, for one test.
class CapturedLog {
 public:
  CapturedLog(std::ostringstream& out, spdlog::level::level_enum level)
      : previous_(spdlog::default_logger()) {
    auto logger = std::make_shared<spdlog::logger>(
        "scallopd", std::make_shared<spdlog::sinks::ostream_sink_st>(out));
    logger->set_level(level);
    spdlog::set_default_logger(logger);
  }
  ~CapturedLog() { spdlog::set_default_logger(previous_); }

 private:
  std::shared_ptr<spdlog::logger> previous_;
};

// Reads what is in the pipe now, without waiting.
std::string Drain(int fd) {
  std::string text;
  char buffer[4096];
  ssize_t n = 0;
  while ((n = ::read(fd, buffer, sizeof buffer)) > 0) text.append(buffer, static_cast<size_t>(n));
  return text;
}

class Pipe {
 public:
  Pipe() {
    EXPECT_EQ(::pipe(fds_), 0);
    ::fcntl(fds_[0], F_SETFL, O_NONBLOCK);
  }
  ~Pipe() {
    ::close(fds_[0]);
    ::close(fds_[1]);
  }
  int read_end() const { return fds_[0]; }
  int write_end() const { return fds_[1]; }

 private:
  int fds_[2] = {-1, -1};
};

const World kWorld = *World::Create({.seed = 7, .min_distance = 0.5});

TEST(RequestLogTest, AnAnsweredCallsLineHoldsEveryField) {
  std::ostringstream out;
  {
    const CapturedLog captured(out, spdlog::level::info);
    RequestLog log("GetPoints");
    log.set_world(kWorld);
    log.set_rect({-1.5, 2, 64, 66.25});
    log.add_points(3497);
    log.Finish(grpc::Status::OK);
  }
  const std::string line = out.str();
  EXPECT_NE(line.find("[info] GetPoints world=\"" + kWorld.Describe() + "\" "), std::string::npos)
      << line;
  EXPECT_NE(line.find(" rect=[-1.5,64)x[2,66.25) points=3497 ms="), std::string::npos) << line;
  EXPECT_NE(line.find(" code=OK\n"), std::string::npos) << line;
  EXPECT_EQ(std::count(line.begin(), line.end(), '\n'), 1) << line;
}

// The line is formatted once, by the log itself: braces in its text (here
// the method's name) reach the log as they are, never read as a format.
TEST(RequestLogTest, TheLineIsNotFormattedTwice) {
  std::ostringstream out;
  {
    const CapturedLog captured(out, spdlog::level::info);
    RequestLog log("Get{}Points{:x}");
    log.set_rect({0, 0, 1e-300, 1e300});
    log.Finish(grpc::Status::OK);
  }
  EXPECT_NE(out.str().find("[info] Get{}Points{:x} world=\"-\" rect=[0,1e-300)x[0,1e+300) "),
            std::string::npos)
      << out.str();
}

// A configured world's line uses the description the registry made once; an
// inline world's is made when the line is written; both are Describe()'s.
TEST(RequestLogTest, ConfiguredAndInlineWorldsAreDescribedAlike) {
  const World inline_world = *World::Create({.seed = 11, .algorithm = WorldAlgorithm::kA1});
  const WorldRegistry registry({{"coast", kWorld}}, "coast");
  v1::GetPointsRequest by_name;
  by_name.set_world_name("coast");
  v1::GetPointsRequest by_default;
  v1::GetPointsRequest in_line;
  *in_line.mutable_world() = WorldToMessage(inline_world);
  for (const auto& [request, world] : {std::pair{by_name, kWorld}, std::pair{by_default, kWorld},
                                       std::pair{in_line, inline_world}}) {
    ResolvedWorld resolved;
    ASSERT_TRUE(registry.Resolve(request, resolved).ok());
    EXPECT_EQ(resolved.description == nullptr, request.has_world());
    std::ostringstream out;
    {
      const CapturedLog captured(out, spdlog::level::info);
      RequestLog log("GetPoints");
      log.set_world(resolved.world, resolved.description);
      log.Finish(grpc::Status::OK);
    }
    EXPECT_NE(out.str().find(" world=\"" + world.Describe() + "\" "), std::string::npos)
        << out.str();
  }
}

TEST(RequestLogTest, AFailedCallsLineNamesItsCodeAndMessageAtWarn) {
  std::ostringstream out;
  {
    const CapturedLog captured(out, spdlog::level::warn);
    RequestLog answered("GetPoints");
    answered.set_world(kWorld);
    answered.Finish(grpc::Status::OK);
    RequestLog failed("Verify");  // no world resolved: "-"
    failed.Finish({grpc::StatusCode::INVALID_ARGUMENT, "rect: required"});
  }
  const std::string text = out.str();
  EXPECT_EQ(text.find("code=OK"), std::string::npos) << "warn drops answered calls: " << text;
  EXPECT_NE(text.find("[warning] Verify world=\"-\" rect=- points=0 ms="), std::string::npos)
      << text;
  EXPECT_NE(text.find(" code=INVALID_ARGUMENT message=\"rect: required\"\n"), std::string::npos)
      << text;
}

TEST(RequestLogTest, CallsAreCountedWhateverTheLevel) {
  std::ostringstream out;
  RequestMetrics metrics;
  {
    const CapturedLog captured(out, spdlog::level::off);
    RequestLog log("GetPoints", &metrics);
    log.add_points(12);
    log.Finish(grpc::Status::OK);
  }
  EXPECT_TRUE(out.str().empty());
  const std::string exposition = metrics.Exposition({}, 0);
  EXPECT_NE(exposition.find("scallop_requests_total{method=\"GetPoints\",code=\"OK\"} 1\n"),
            std::string::npos)
      << exposition;
  EXPECT_NE(exposition.find("scallop_points_served_total{method=\"GetPoints\"} 12\n"),
            std::string::npos)
      << exposition;
}

// One logger writing the same lines through spdlog's ostream sink (a line at
// a time, into `expected`) and through a batching sink into a pipe.
struct TwinSinks {
  explicit TwinSinks(size_t capacity)
      : logger(std::in_place, "scallopd",
               spdlog::sinks_init_list{
                   std::make_shared<spdlog::sinks::ostream_sink_st>(expected),
                   std::make_shared<BufferedLogSink>(pipe.write_end(), capacity)}) {}
  std::string Written() const { return Drain(pipe.read_end()); }

  Pipe pipe;
  std::ostringstream expected;
  std::optional<spdlog::logger> logger;  // reset: the sinks' end
};

// The descriptor gets nothing until the buffer fills, a warning comes or the
// logger flushes, and then everything held, in order.
TEST(BufferedLogSinkTest, WritesOnlyWhenFullFlushedOrWarned) {
  TwinSinks twin(200);  // room for three or four lines of about 55 bytes
  spdlog::logger& logger = *twin.logger;
  logger.flush_on(spdlog::level::warn);

  logger.info("GetPoints line {}", 1);
  logger.info("GetPoints line {}", 2);
  EXPECT_EQ(twin.Written(), "") << "two short lines are held";
  std::string written;
  int lines = 2;
  while (written.empty() && lines < 10) {
    logger.info("GetPoints line {}", ++lines);
    written = twin.Written();
  }
  EXPECT_LE(lines, 4) << "200 bytes hold at most three lines";
  EXPECT_EQ(written, twin.expected.str()) << "full: every held line at once";

  logger.info("held again");
  EXPECT_EQ(twin.Written(), "");
  logger.warn("a warning flushes");
  written += twin.Written();
  EXPECT_EQ(written, twin.expected.str());

  logger.info("at the end");
  EXPECT_EQ(twin.Written(), "");
  logger.flush();
  written += twin.Written();
  EXPECT_EQ(written, twin.expected.str());
}

TEST(BufferedLogSinkTest, TheDescriptorGetsEveryLineInOrder) {
  TwinSinks twin(512);
  twin.logger->set_level(spdlog::level::debug);
  for (int k = 0; k < 200; ++k) {
    if (k % 37 == 36) {
      twin.logger->warn("call {} failed", k);
    } else {
      twin.logger->info("call {} answered", k);
    }
  }
  twin.logger.reset();  // the sink's end writes the rest
  EXPECT_EQ(twin.Written(), twin.expected.str());
}

}  // namespace
}  // namespace scallop::server
