// The log sink of scallopd: lines gathered in memory and written to a file
// descriptor (stderr) in batches, instead of a write(2) and a flush a line.
// At info level every call leaves a line, and a warm GetPoints is answered in
// tens of microseconds: writing each line on its own (a write(2) a call) was
// about 4% of scallopd's CPU under the warm load, some 6 us a call (perf).
// Lines reach the descriptor when the buffer fills, when
// the logger flushes (every second from main, and at once for warnings and
// errors: spdlog's flush_on), and when the sink is destroyed.
#pragma once

#include <spdlog/sinks/base_sink.h>

#include <cstddef>
#include <mutex>
#include <string>

namespace scallop::server {

class BufferedLogSink final : public spdlog::sinks::base_sink<std::mutex> {
 public:
  // Writes to `fd` (not owned; it must outlive the sink) once `capacity`
  // bytes of lines are held, or on flush. Thread-safe (base_sink's mutex).
  explicit BufferedLogSink(int fd, size_t capacity = kDefaultCapacity);
  // Writes what is held.
  ~BufferedLogSink() override;

  // 64 KiB: a few hundred call lines, one write(2) for them all.
  static constexpr size_t kDefaultCapacity = size_t{64} << 10;

 private:
  void sink_it_(const spdlog::details::log_msg& message) override;
  void flush_() override;
  // Writes the buffer whole (retrying short writes and EINTR) and empties it;
  // a descriptor that refuses the bytes loses them: logging never blocks
  // calls on an error.
  void WriteHeld();

  const int fd_;
  const size_t capacity_;
  std::string held_;
};

}  // namespace scallop::server
