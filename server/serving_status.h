// The health check's answer, as balancers and Kubernetes readiness read it:
// NOT_SERVING from SIGTERM on (draining, for good) and while the unary
// budget is saturated (admission_budget.h; when not_serving_when_saturated),
// SERVING otherwise. Applies to every service name of gRPC's health service.
#pragma once

#include <grpcpp/health_check_service_interface.h>

#include <mutex>

namespace scallop::server {

class ServingStatus {
 public:
  // `health` must outlive this. Starts SERVING.
  explicit ServingStatus(grpc::HealthCheckServiceInterface* health) : health_(health) {}

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
