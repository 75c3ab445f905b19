// Load shedding: at most N requests in flight; beyond that a request is refused
// at once with RESOURCE_EXHAUSTED, so overload costs clients a retry instead
// of growing queues and deadlines missed by everyone.
#pragma once

#include <algorithm>
#include <atomic>

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
  // Admitted calls now (a refused one may count for an instant: clamped).
  int in_flight() const { return std::min(in_flight_.load(), limit_); }

 private:
  const int limit_;
  std::atomic<int> in_flight_{0};
};

}  // namespace scallop::server
