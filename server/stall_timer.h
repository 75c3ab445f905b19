// A stream call's watchdog: armed while the call waits on its client (a write
// not yet taken, an update not yet sent), it ends the call with
// DEADLINE_EXCEEDED when the wait outlasts its limit, so a client that went
// quiet cannot hold its stream slot for ever.
#pragma once

#include <grpc/grpc.h>
#include <grpcpp/alarm.h>
#include <grpcpp/server_context.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

namespace scallop::server {

class StallTimer {
 public:
  // `context` must be the call's and outlive the timer.
  explicit StallTimer(grpc::CallbackServerContext* context);

  // Starts a wait of `seconds`: unless Disarm comes first, the call is
  // cancelled with DEADLINE_EXCEEDED and `message` (sent in the trailers,
  // which flow control does not hold back), and its pending operation fails.
  // Arm and Disarm are the reactor's, never called concurrently.
  void Arm(double seconds, std::shared_ptr<const std::string> message);
  void Disarm();

  // Whether a wait ran out: what made the pending operation fail.
  bool fired() const { return watch_->fired; }

 private:
  // What the alarm's callback touches (it can run after the reactor is
  // gone): the call, held by a reference of our own, and the wait watched.
  struct Watch {
    explicit Watch(grpc_call* call_to_cancel) : call(call_to_cancel) { grpc_call_ref(call); }
    ~Watch() { grpc_call_unref(call); }
    Watch(const Watch&) = delete;
    Watch& operator=(const Watch&) = delete;

    grpc_call* const call;
    std::atomic<uint64_t> watched = 0;  // 0: no wait
    std::atomic<bool> fired = false;
  };

  std::shared_ptr<Watch> watch_;
  std::unique_ptr<grpc::Alarm> alarm_;
  uint64_t waits_ = 0;
};

// "10", "0.25": seconds as set, for messages (shortest exact text).
std::string SecondsText(double seconds);

}  // namespace scallop::server
