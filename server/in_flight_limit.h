// Load shedding: at most N calls of a kind in flight; beyond that a call is
// refused at once with RESOURCE_EXHAUSTED, so overload costs clients a retry
// instead of growing queues and deadlines missed by everyone.
#pragma once

#include <grpcpp/support/status.h>

#include <algorithm>
#include <atomic>
#include <string>

namespace scallop::server {

class InFlightLimit {
 public:
  // `setting` names the limit in refusals, e.g. "max_in_flight".
  InFlightLimit(int limit, std::string setting) : limit_(limit), setting_(std::move(setting)) {}

  // True (and counted) when under the limit; pair with Release. Lock-free.
  bool TryAdmit() {
    if (in_flight_.fetch_add(1) < limit_) return true;
    in_flight_.fetch_sub(1);
    return false;
  }
  void Release() { in_flight_.fetch_sub(1); }
  int limit() const { return limit_; }
  // The status a refused call gets: it names the setting and asks for backoff.
  grpc::Status Refusal() const {
    return {grpc::StatusCode::RESOURCE_EXHAUSTED, "server: " + std::to_string(limit_) +
                                                      " calls already in flight (" + setting_ +
                                                      "); retry with backoff"};
  }
  // Admitted calls now (a refused one may count for an instant: clamped).
  int in_flight() const { return std::min(in_flight_.load(), limit_); }

 private:
  const int limit_;
  const std::string setting_;
  std::atomic<int> in_flight_{0};
};

}  // namespace scallop::server
