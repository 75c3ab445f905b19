// The service's shared machinery: the unary call path, and the checks every call shares.
#include "server/scallop_service.h"

#include <boost/asio/post.hpp>

namespace scallop::server {

grpc::Status ServiceContext::CheckNearestRegions(int64_t regions, const char* field,
                                                 const char* advice) const {
  if (regions <= config.max_nearest_regions) return grpc::Status::OK;
  return {grpc::StatusCode::INVALID_ARGUMENT,
          std::string(field) + ": lie in " + std::to_string(regions) +
              " distinct regions of 16 min_distance, at most " +
              std::to_string(config.max_nearest_regions) + " (max_nearest_regions); " + advice};
}

grpc::ServerUnaryReactor* ScallopService::RunUnary(grpc::CallbackServerContext* context,
                                                   const char* method, const grpc::Status& access,
                                                   UnaryWork work) {
  return RunUnaryInlineFirst(
      context, method, access, [](RequestLog&) { return std::optional<grpc::Status>(); },
      std::move(work));
}

grpc::ServerUnaryReactor* ScallopService::RunUnaryInlineFirst(grpc::CallbackServerContext* context,
                                                              const char* method,
                                                              const grpc::Status& access,
                                                              InlineWork quick, UnaryWork work) {
  grpc::ServerUnaryReactor* reactor = context->DefaultReactor();
  auto log = std::make_shared<RequestLog>(method, shared_.metrics);
  if (!access.ok()) {
    log->Finish(access);
    reactor->Finish(access);
    return reactor;
  }
  if (!shared_.unary_in_flight.TryAdmit()) {
    const grpc::Status status = shared_.unary_in_flight.Refusal();
    log->Finish(status);
    reactor->Finish(status);
    return reactor;
  }
  if (std::optional<grpc::Status> status = quick(*log)) {
    log->Finish(*status);
    shared_.unary_in_flight.Release();
    reactor->Finish(*status);
    return reactor;
  }
  boost::asio::post(shared_.request_pool, [this, context, reactor, log, work = std::move(work)] {
    const grpc::Status status = context->IsCancelled()
                                    ? grpc::Status(grpc::StatusCode::CANCELLED, "client cancelled")
                                    : work(*log);
    log->Finish(status);
    shared_.unary_in_flight.Release();
    reactor->Finish(status);
  });
  return reactor;
}

}  // namespace scallop::server
