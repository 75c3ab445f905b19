// One log line per request: method, world, rectangle, points, milliseconds and
// status code (with the message when it failed), written when the call ends,
// and the same call counted in the server's metrics when it has them. The
// line is formatted only when the log level keeps it (the world's
// description too), so `warn` makes a successful call's log nearly free.
#pragma once

#include <grpcpp/support/status.h>

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include "scallop/geometry/rect.h"
#include "scallop/plane/world.h"
#include "server/request_metrics.h"

namespace scallop::server {

class RequestLog {
 public:
  // `metrics` (may be null) must outlive the log.
  explicit RequestLog(std::string method, RequestMetrics* metrics = nullptr)
      : method_(std::move(method)), metrics_(metrics), start_(std::chrono::steady_clock::now()) {}

  // The call's world; `description` (may be null: made when the line is
  // written) must then be world.Describe() and outlive the log.
  void set_world(const World& world, const std::string* description = nullptr) {
    if (description != nullptr) {
      world_description_ = description;
    } else {
      world_ = world;
    }
  }
  void set_rect(const Rect& rect) { rect_ = rect; }
  void add_points(int64_t count) { points_ += count; }

  // Writes the line and records the call. Call once, when its status is known.
  void Finish(const grpc::Status& status) const;

 private:
  std::string method_;
  RequestMetrics* metrics_;
  std::chrono::steady_clock::time_point start_;
  const std::string* world_description_ = nullptr;
  std::optional<World> world_;  // else described when the line is written
  std::optional<Rect> rect_;
  int64_t points_ = 0;
};

}  // namespace scallop::server
