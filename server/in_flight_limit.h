// Load shedding: at most N requests in flight; beyond that a request is refused
// at once with RESOURCE_EXHAUSTED, so overload costs clients a retry instead
// of growing queues and deadlines missed by everyone.
#pragma once

#include <grpcpp/support/status.h>

#include <algorithm>
#include <atomic>
#include <string>

namespace scallop::server {

class InFlightLimit {
 public:
  explicit InFlightLimit(int limit) : limit_(limit) {}

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
    return {grpc::StatusCode::RESOURCE_EXHAUSTED,
            "server: " + std::to_string(limit_) +
                " requests already in flight (max_in_flight); retry with backoff"};
  }
  // Admitted calls now (a refused one may count for an instant: clamped).
  int in_flight() const { return std::min(in_flight_.load(), limit_); }

 private:
  const int limit_;
  std::atomic<int> in_flight_{0};
};

}  // namespace scallop::server
