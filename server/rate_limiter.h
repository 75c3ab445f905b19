// Per-client rate limits: a token bucket per client key (client_key.h), so
// that one client's burst of calls cannot take the service from the others.
// A refused call learns how long to wait (retry_status.h).
#pragma once

#include <chrono>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_map>

namespace scallop::server {

class RateLimiter {
 public:
  using Clock = std::chrono::steady_clock;

  // `calls_per_second` <= 0: no limit. Otherwise each client may make `burst`
  // calls at once and `calls_per_second` on average. REQUIRES: burst >= 1.
  RateLimiter(double calls_per_second, double burst) : rate_(calls_per_second), burst_(burst) {}

  bool enabled() const { return rate_ > 0; }

  // Takes one call from `client`'s bucket: nullopt when allowed, else the
  // seconds until the bucket holds a call again. Thread-safe; O(1) amortised.
  // The table forgets clients whose bucket has refilled once it holds
  // kSweepAt clients, so it stays as large as the clients active within the
  // last burst / rate seconds.
  std::optional<double> TryTake(const std::string& client, Clock::time_point now = Clock::now());

  // Clients the table holds now, for tests.
  size_t clients() const;

  static constexpr size_t kSweepAt = 4096;

 private:
  struct Bucket {
    double calls;  // available, <= burst_
    Clock::time_point at;
  };
  double Refilled(const Bucket& bucket, Clock::time_point now) const;

  const double rate_;
  const double burst_;
  mutable std::mutex mutex_;
  std::unordered_map<std::string, Bucket> buckets_;
  size_t sweep_at_ = kSweepAt;
};

}  // namespace scallop::server
