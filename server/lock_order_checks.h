// absl's lock-order checks, which gRPC's every lock pays for in the Debian
// build (docs/performance.md, "Service under load").
#pragma once

#include <absl/synchronization/mutex.h>

namespace scallop::server {

// Turns off absl's lock-order (deadlock) detection for the whole process.
// Debian builds absl without NDEBUG, so every absl::Mutex::Lock, and with it
// every one of the thirty-odd gRPC locks a unary call takes, records the lock
// in a graph of lock orders: about a fifth of the instructions gRPC spends on
// a warm GetPoints (callgrind). A release build of absl does not check; the
// null server the load benchmark compares scallopd with calls this too, so
// that both run the same transport. Call before serving; O(1).
inline void TurnOffLockOrderChecks() {
  absl::SetMutexDeadlockDetectionMode(absl::OnDeadlockCycle::kIgnore);
}

}  // namespace scallop::server
