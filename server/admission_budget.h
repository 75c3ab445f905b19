// Load shedding that no one client can exhaust alone. A budget admits calls
// of one kind (unary, or streaming) while there is room, and refuses the rest
// at once with RESOURCE_EXHAUSTED naming the setting that refused them, so
// overload costs a client a retry instead of growing queues and deadlines
// missed by everyone. Room is counted three ways:
//  - calls in flight, at most max_calls;
//  - their cost, at most max_cost: a call's cost is the regions it may touch
//    (request_cost.h), so a few huge calls weigh as much as many small ones;
//  - per client (client_key.h), at most client_share of both. A client with
//    nothing in flight may always start one call, however costly, when the
//    whole budget has room for it.
// It also tells when it is saturated (health_status.h turns that into
// NOT_SERVING): from a refusal for want of room until half of it is free.
#pragma once

#include <grpcpp/support/status.h>

#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <unordered_map>

namespace scallop::server {

struct AdmissionLimits {
  int max_calls = 64;
  int64_t max_cost = 65536;
  double client_share = 0.5;  // in (0, 1]
  // Settings named in refusals.
  std::string calls_setting = "max_in_flight";
  std::string cost_setting = "max_in_flight_cost";
};

class AdmissionBudget {
 public:
  explicit AdmissionBudget(AdmissionLimits limits);

  // OK (the call now holds `cost`, clamped to [1, max_cost]), or the refusal.
  // Pair an OK with Release(client, cost) with the same arguments. O(1).
  grpc::Status TryAdmit(const std::string& client, int64_t cost);
  void Release(const std::string& client, int64_t cost);

  // Called with true when the budget becomes saturated and false when it is
  // half free again, under the budget's lock (it must not call back).
  void OnSaturationChange(std::function<void(bool)> callback);

  int in_flight() const;
  int64_t cost_in_flight() const;
  bool saturated() const;
  const AdmissionLimits& limits() const { return limits_; }

 private:
  struct Usage {
    int calls = 0;
    int64_t cost = 0;
  };
  int64_t Clamp(int64_t cost) const;
  void SetSaturated(bool saturated);

  const AdmissionLimits limits_;
  const int client_calls_;     // per client
  const int64_t client_cost_;  // per client
  mutable std::mutex mutex_;
  Usage total_;
  std::unordered_map<std::string, Usage> clients_;  // only clients with calls in flight
  bool saturated_ = false;
  std::function<void(bool)> on_saturation_;
};

}  // namespace scallop::server
