#include "server/admission_budget.h"

#include <algorithm>
#include <cmath>

#include "scallop/base/number_text.h"

namespace scallop::server {

AdmissionBudget::AdmissionBudget(AdmissionLimits limits)
    : limits_(std::move(limits)),
      client_calls_(std::max(1, static_cast<int>(limits_.max_calls * limits_.client_share))),
      client_cost_(std::max<int64_t>(
          1, static_cast<int64_t>(static_cast<double>(limits_.max_cost) * limits_.client_share))) {}

int64_t AdmissionBudget::Clamp(int64_t cost) const {
  return std::clamp<int64_t>(cost, 1, limits_.max_cost);
}

grpc::Status AdmissionBudget::TryAdmit(const std::string& client, int64_t cost) {
  cost = Clamp(cost);
  std::lock_guard lock(mutex_);
  if (total_.calls >= limits_.max_calls) {
    SetSaturated(true);
    return {grpc::StatusCode::RESOURCE_EXHAUSTED,
            "server: " + std::to_string(limits_.max_calls) + " calls already in flight (" +
                limits_.calls_setting + "); retry with backoff"};
  }
  if (total_.cost + cost > limits_.max_cost) {
    SetSaturated(true);
    return {grpc::StatusCode::RESOURCE_EXHAUSTED,
            "server: calls in flight may touch " + std::to_string(total_.cost) +
                " regions and this one " + std::to_string(cost) + ", over " +
                std::to_string(limits_.max_cost) + " (" + limits_.cost_setting +
                "); retry with backoff, or ask for less at once"};
  }
  Usage& usage = clients_[client];
  if (usage.calls > 0 && (usage.calls >= client_calls_ || usage.cost + cost > client_cost_)) {
    return {grpc::StatusCode::RESOURCE_EXHAUSTED,
            "server: this client already has " + std::to_string(usage.calls) +
                " calls in flight touching " + std::to_string(usage.cost) +
                " regions, its share (max_client_share " + NumberText(limits_.client_share) +
                " of " + limits_.calls_setting + " and " + limits_.cost_setting +
                "); wait for them before starting more"};
  }
  usage.calls += 1;
  usage.cost += cost;
  total_.calls += 1;
  total_.cost += cost;
  return grpc::Status::OK;
}

void AdmissionBudget::Release(const std::string& client, int64_t cost) {
  cost = Clamp(cost);
  std::lock_guard lock(mutex_);
  if (auto it = clients_.find(client); it != clients_.end()) {
    it->second.calls -= 1;
    it->second.cost -= cost;
    if (it->second.calls == 0) clients_.erase(it);
  }
  total_.calls -= 1;
  total_.cost -= cost;
  if (saturated_ && 2 * total_.calls <= limits_.max_calls && 2 * total_.cost <= limits_.max_cost) {
    SetSaturated(false);
  }
}

void AdmissionBudget::SetSaturated(bool saturated) {
  if (saturated == saturated_) return;
  saturated_ = saturated;
  if (on_saturation_) on_saturation_(saturated);
}

void AdmissionBudget::OnSaturationChange(std::function<void(bool)> callback) {
  std::lock_guard lock(mutex_);
  on_saturation_ = std::move(callback);
}

int AdmissionBudget::in_flight() const {
  std::lock_guard lock(mutex_);
  return total_.calls;
}

int64_t AdmissionBudget::cost_in_flight() const {
  std::lock_guard lock(mutex_);
  return total_.cost;
}

bool AdmissionBudget::saturated() const {
  std::lock_guard lock(mutex_);
  return saturated_;
}

}  // namespace scallop::server
