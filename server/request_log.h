// One log line per request: method, world, rectangle, points, milliseconds and
// status code (with the message when it failed), written when the call ends.
#pragma once

#include <grpcpp/support/status.h>

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include "scallop/geometry/rect.h"

namespace scallop::server {

class RequestLog {
 public:
  explicit RequestLog(std::string method)
      : method_(std::move(method)), start_(std::chrono::steady_clock::now()) {}

  void set_world(std::string description) { world_ = std::move(description); }
  void set_rect(const Rect& rect) { rect_ = rect; }
  void add_points(int64_t count) { points_ += count; }

  // Writes the line. Call once, when the call's status is known.
  void Finish(const grpc::Status& status) const;

 private:
  std::string method_;
  std::chrono::steady_clock::time_point start_;
  std::string world_ = "-";
  std::optional<Rect> rect_;
  int64_t points_ = 0;
};

}  // namespace scallop::server
