// The health check's answer, as balancers and Kubernetes readiness read it:
// NOT_SERVING from SIGTERM on (draining, for good) and while the unary
// budget is saturated (admission_budget.h; when not_serving_when_saturated),
// SERVING otherwise: the answer for the server as a whole (service "").
// The service "liveness" says SERVING as long as the process answers: what a
// liveness probe must ask, so that a saturated replica is not restarted.
#pragma once

#include <grpcpp/health_check_service_interface.h>

#include <mutex>

namespace scallop::server {

class ServingStatus {
 public:
  static constexpr const char* kLivenessService = "liveness";

  // `health` must outlive this. Starts SERVING.
  explicit ServingStatus(grpc::HealthCheckServiceInterface* health);

  void SetSaturated(bool saturated);
  void SetDraining();

 private:
  void Apply();  // REQUIRES: mutex_ held

  grpc::HealthCheckServiceInterface* const health_;
  std::mutex mutex_;
  bool saturated_ = false;
  bool draining_ = false;
};

}  // namespace scallop::server
