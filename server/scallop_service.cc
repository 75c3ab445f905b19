// The service's shared machinery: the unary call path, and the checks every call shares.
#include "server/scallop_service.h"

#include <boost/asio/post.hpp>

#include "scallop/base/number_text.h"
#include "scallop/plane/query_rect.h"
#include "server/retry_status.h"

namespace scallop::server {

grpc::Status ServiceContext::Admit(const grpc::ServerContextBase& context, AdmissionBudget& budget,
                                   int64_t cost, std::string& client) {
  client = ClientKey(context, tokens != nullptr);
  return Admit(client, budget, cost);
}

grpc::Status ServiceContext::Admit(const std::string& client, AdmissionBudget& budget, int64_t cost,
                                   double* retry_after) {
  if (const std::optional<double> wait = rate_limiter.TryTake(client)) {
    if (retry_after != nullptr) *retry_after = *wait;
    return ResourceExhaustedRetryAfter(
        "server: this client's calls are over " + NumberText(config.rate_limit_per_second) +
            " a second (rate_limit_per_second, burst rate_limit_burst " +
            NumberText(config.rate_limit_burst) + ")",
        *wait);
  }
  return budget.TryAdmit(client, cost);
}

grpc::Status ServiceContext::CheckNearestRegions(const World& world, int64_t regions,
                                                 const char* field, const char* advice) const {
  if (regions <= config.max_nearest_regions) return grpc::Status::OK;
  return {grpc::StatusCode::INVALID_ARGUMENT,
          std::string(field) + ": lie in " + std::to_string(regions) + " distinct regions of " +
              RegionSideText(world) + ", at most " + std::to_string(config.max_nearest_regions) +
              " (max_nearest_regions); " + advice};
}

grpc::ServerUnaryReactor* ScallopService::RunUnary(grpc::CallbackServerContext* context,
                                                   const char* method, const grpc::Status& access,
                                                   int64_t cost, UnaryWork work) {
  return RunUnaryInlineFirst(
      context, method, access, cost, [](RequestLog&) { return std::optional<grpc::Status>(); },
      std::move(work));
}

void ScallopService::RunOnPool(grpc::CallbackServerContext* context,
                               grpc::ServerUnaryReactor* reactor, RequestLog log,
                               std::string client, int64_t cost, UnaryWork work) {
  boost::asio::post(shared_.request_pool, [this, context, reactor, log = std::move(log),
                                           client = std::move(client), cost,
                                           work = std::move(work)]() mutable {
    const grpc::Status status = context->IsCancelled()
                                    ? grpc::Status(grpc::StatusCode::CANCELLED, "client cancelled")
                                    : work(log);
    log.Finish(status);
    shared_.unary_in_flight.Release(client, cost);
    reactor->Finish(status);
  });
}

}  // namespace scallop::server
