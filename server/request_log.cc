// Request log lines, through spdlog (stderr).
#include "server/request_log.h"

#include <fmt/compile.h>
#include <spdlog/spdlog.h>

#include <iterator>
#include <string_view>

#include "status_code_name.h"

namespace scallop::server {

void RequestLog::Finish(const grpc::Status& status) const {
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (metrics_ != nullptr) metrics_->Record(method_, status.error_code(), seconds, points_);
  // A warm tile is answered in tens of microseconds: skip the formatting of
  // lines the level drops.
  if (!spdlog::should_log(status.ok() ? spdlog::level::info : spdlog::level::warn)) return;
  const double milliseconds = seconds * 1000;
  // Views, so a configured world's description is not copied a call.
  const std::string described = world_description_ == nullptr && world_ ? world_->Describe() : "";
  std::string_view world = "-";
  if (world_description_ != nullptr) {
    world = *world_description_;
  } else if (world_) {
    world = described;
  }
  // Compiled formats: parsing them a call was half the line's cost (callgrind).
  fmt::memory_buffer rect;
  if (rect_) {
    fmt::format_to(std::back_inserter(rect), FMT_COMPILE("[{},{})x[{},{})"), rect_->x0, rect_->x1,
                   rect_->y0, rect_->y1);
  } else {
    rect.push_back('-');
  }
  const std::string_view rect_text(rect.data(), rect.size());
  if (status.ok()) {
    fmt::memory_buffer line;
    fmt::format_to(std::back_inserter(line),
                   FMT_COMPILE("{} world=\"{}\" rect={} points={} ms={:.1f} code=OK"), method_,
                   world, rect_text, points_, milliseconds);
    spdlog::info(std::string_view(line.data(), line.size()));  // as it is: no format
  } else {
    spdlog::warn("{} world=\"{}\" rect={} points={} ms={:.1f} code={} message=\"{}\"", method_,
                 world, rect_text, points_, milliseconds, StatusCodeName(status.error_code()),
                 status.error_message());
  }
}

}  // namespace scallop::server
