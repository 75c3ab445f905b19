#include "server/serving_status.h"

#include <spdlog/spdlog.h>

namespace scallop::server {

ServingStatus::ServingStatus(grpc::HealthCheckServiceInterface* health) : health_(health) {
  health_->SetServingStatus(kLivenessService, true);
}

void ServingStatus::SetSaturated(bool saturated) {
  std::lock_guard lock(mutex_);
  if (saturated == saturated_) return;
  saturated_ = saturated;
  if (!draining_) {
    spdlog::warn(saturated ? "saturated: health NOT_SERVING until half the budget is free"
                           : "no longer saturated: health SERVING");
  }
  Apply();
}

void ServingStatus::SetDraining() {
  std::lock_guard lock(mutex_);
  draining_ = true;
  Apply();
}

void ServingStatus::Apply() {
  // Sets every service gRPC knows, "liveness" too, which stays SERVING.
  health_->SetServingStatus(!draining_ && !saturated_);
  health_->SetServingStatus(kLivenessService, true);
}

}  // namespace scallop::server
