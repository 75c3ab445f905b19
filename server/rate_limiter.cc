#include "server/rate_limiter.h"

#include <algorithm>

namespace scallop::server {

double RateLimiter::Refilled(const Bucket& bucket, Clock::time_point now) const {
  const double elapsed = std::chrono::duration<double>(now - bucket.at).count();
  return std::min(burst_, bucket.calls + std::max(0.0, elapsed) * rate_);
}

std::optional<double> RateLimiter::TryTake(const std::string& client, Clock::time_point now) {
  if (!enabled()) return std::nullopt;
  std::lock_guard lock(mutex_);
  if (buckets_.size() >= sweep_at_) {
    // Full buckets carry no state worth keeping: a new one starts full too.
    std::erase_if(buckets_,
                  [&](const auto& entry) { return Refilled(entry.second, now) >= burst_; });
    // Many active clients: sweep again only once the table has doubled.
    sweep_at_ = std::max(kSweepAt, 2 * buckets_.size());
  }
  auto [it, inserted] = buckets_.try_emplace(client, Bucket{burst_, now});
  Bucket& bucket = it->second;
  bucket.calls = Refilled(bucket, now);
  bucket.at = now;
  if (bucket.calls >= 1) {
    bucket.calls -= 1;
    return std::nullopt;
  }
  return (1 - bucket.calls) / rate_;
}

size_t RateLimiter::clients() const {
  std::lock_guard lock(mutex_);
  return buckets_.size();
}

}  // namespace scallop::server
