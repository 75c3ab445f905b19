// BufferedLogSink: formatting as spdlog's other sinks, writing in batches.
#include "server/buffered_log_sink.h"

#include <unistd.h>

#include <cerrno>

namespace scallop::server {

BufferedLogSink::BufferedLogSink(int fd, size_t capacity) : fd_(fd), capacity_(capacity) {
  held_.reserve(capacity_);
}

BufferedLogSink::~BufferedLogSink() {
  const std::lock_guard lock(mutex_);
  WriteHeld();
}

void BufferedLogSink::sink_it_(const spdlog::details::log_msg& message) {
  spdlog::memory_buf_t formatted;
  formatter_->format(message, formatted);
  held_.append(formatted.data(), formatted.size());
  if (held_.size() >= capacity_) WriteHeld();
}

void BufferedLogSink::flush_() { WriteHeld(); }

void BufferedLogSink::WriteHeld() {
  size_t written = 0;
  while (written < held_.size()) {
    const ssize_t n = ::write(fd_, held_.data() + written, held_.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    written += static_cast<size_t>(n);
  }
  held_.clear();
}

}  // namespace scallop::server
