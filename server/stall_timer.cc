// StallTimer: one grpc::Alarm per wait, and the cancellation it fires.
#include "server/stall_timer.h"

#include <fmt/format.h>

#include <chrono>

namespace scallop::server {

StallTimer::StallTimer(grpc::CallbackServerContext* context)
    : watch_(std::make_shared<Watch>(context->c_call())) {}

void StallTimer::Arm(double seconds, std::shared_ptr<const std::string> message) {
  const uint64_t wait = ++waits_;
  watch_->watched = wait;
  // A fresh alarm per wait: replacing the last one cancels it.
  alarm_ = std::make_unique<grpc::Alarm>();
  alarm_->Set(std::chrono::system_clock::now() +
                  std::chrono::duration_cast<std::chrono::system_clock::duration>(
                      std::chrono::duration<double>(seconds)),
              [watch = watch_, wait, message = std::move(message)](bool ran_out) {
                // Should the wait end in the same instant, the call still
                // ends: the client was that slow.
                if (!ran_out || watch->watched != wait) return;
                watch->fired = true;
                grpc_call_cancel_with_status(watch->call, GRPC_STATUS_DEADLINE_EXCEEDED,
                                             message->c_str(), nullptr);
              });
}

void StallTimer::Disarm() {
  watch_->watched = 0;
  if (alarm_) alarm_->Cancel();
}

std::string SecondsText(double seconds) { return fmt::format("{}", seconds); }

}  // namespace scallop::server
