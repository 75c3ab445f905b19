// The service's shared machinery: construction and the unary call path.
#include "scallop_service.h"

#include <boost/asio/post.hpp>

namespace scallop::server {

ScallopService::ScallopService(const ServerConfig& config, const WorldRegistry& worlds,
                               const PageTokenCodec& page_tokens, PlaneEngine& engine,
                               boost::asio::thread_pool& request_pool, RequestMetrics* metrics)
    : config_(config),
      worlds_(worlds),
      page_tokens_(page_tokens),
      engine_(engine),
      request_pool_(request_pool),
      metrics_(metrics),
      in_flight_(config.max_in_flight, "max_in_flight"),
      streams_in_flight_(config.max_streams_in_flight, "max_streams_in_flight") {}

grpc::Status ScallopService::CheckNearestRegions(int64_t regions, const char* field,
                                                 const char* advice) const {
  if (regions <= config_.max_nearest_regions) return grpc::Status::OK;
  return {grpc::StatusCode::INVALID_ARGUMENT,
          std::string(field) + ": lie in " + std::to_string(regions) +
              " distinct regions of 16 min_distance, at most " +
              std::to_string(config_.max_nearest_regions) + " (max_nearest_regions); " + advice};
}

grpc::ServerUnaryReactor* ScallopService::RunUnary(grpc::CallbackServerContext* context,
                                                   const char* method, UnaryWork work) {
  return RunUnaryInlineFirst(
      context, method, [](RequestLog&) { return std::optional<grpc::Status>(); }, std::move(work));
}

grpc::ServerUnaryReactor* ScallopService::RunUnaryInlineFirst(grpc::CallbackServerContext* context,
                                                              const char* method, InlineWork quick,
                                                              UnaryWork work) {
  grpc::ServerUnaryReactor* reactor = context->DefaultReactor();
  auto log = std::make_shared<RequestLog>(method, metrics_);
  if (!in_flight_.TryAdmit()) {
    const grpc::Status status = in_flight_.Refusal();
    log->Finish(status);
    reactor->Finish(status);
    return reactor;
  }
  if (std::optional<grpc::Status> status = quick(*log)) {
    log->Finish(*status);
    in_flight_.Release();
    reactor->Finish(*status);
    return reactor;
  }
  boost::asio::post(request_pool_, [this, context, reactor, log, work = std::move(work)] {
    const grpc::Status status = context->IsCancelled()
                                    ? grpc::Status(grpc::StatusCode::CANCELLED, "client cancelled")
                                    : work(*log);
    log->Finish(status);
    in_flight_.Release();
    reactor->Finish(status);
  });
  return reactor;
}

}  // namespace scallop::server
