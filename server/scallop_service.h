// The scallop.v1.Scallop service on gRPC's callback API: no thread per
// request. Handlers hand each call to the request pool, which validates and
// answers it; the engine generates regions on its own pool and shares one
// region cache among all requests, so a region is generated once however many
// requests want it at once. Each RPC's body lives in its own file and reaches
// what calls share through the ServiceContext.
#pragma once

#include <functional>
#include <optional>

#include "scallop/v1/scallop.grpc.pb.h"
#include "server/service_context.h"

namespace scallop::server {

// GetPoints is served on raw bytes: its common answer is written straight
// into the slices gRPC sends (packed_answer.h); its request is parsed and
// checked as any other call's.
class ScallopService final
    : public v1::Scallop::WithRawCallbackMethod_GetPoints<v1::Scallop::CallbackService> {
 public:
  // All references must outlive the service; the pool must outlive every call.
  // `metrics` (may be null: not recorded) counts every finished call.
  // `tokens` (may be null: no token needed) are the bearer tokens calls need.
  ScallopService(const ServerConfig& config, const WorldRegistry& worlds,
                 const PageTokenCodec& page_tokens, PlaneEngine& engine,
                 boost::asio::thread_pool& request_pool, RequestMetrics* metrics = nullptr,
                 const TokenTable* tokens = nullptr)
      : shared_(config, worlds, page_tokens, engine, request_pool, metrics, tokens) {}

  grpc::ServerUnaryReactor* GetPoints(grpc::CallbackServerContext* context,
                                      const grpc::ByteBuffer* request,
                                      grpc::ByteBuffer* response) override;
  grpc::ServerWriteReactor<v1::PointsChunk>* StreamPoints(
      grpc::CallbackServerContext* context, const v1::StreamPointsRequest* request) override;
  grpc::ServerUnaryReactor* Verify(grpc::CallbackServerContext* context,
                                   const v1::VerifyRequest* request,
                                   v1::VerifyResponse* response) override;
  grpc::ServerUnaryReactor* DescribeWorld(grpc::CallbackServerContext* context,
                                          const v1::DescribeWorldRequest* request,
                                          v1::DescribeWorldResponse* response) override;
  grpc::ServerUnaryReactor* GetServerInfo(grpc::CallbackServerContext* context,
                                          const v1::GetServerInfoRequest* request,
                                          v1::GetServerInfoResponse* response) override;
  grpc::ServerUnaryReactor* Nearest(grpc::CallbackServerContext* context,
                                    const v1::NearestRequest* request,
                                    v1::NearestResponse* response) override;
  grpc::ServerUnaryReactor* NoiseGrid(grpc::CallbackServerContext* context,
                                      const v1::NoiseGridRequest* request,
                                      v1::NoiseGridResponse* response) override;
  grpc::ServerBidiReactor<v1::FollowRequest, v1::FollowResponse>* Follow(
      grpc::CallbackServerContext* context) override;

  // Calls admitted and not yet finished (unary and streaming), for the metrics.
  int requests_in_flight() const { return shared_.requests_in_flight(); }
  // What calls share, for the HTTP tiles (http_api.h), which take the same
  // slots, engine and tokens.
  ServiceContext& context() { return shared_; }
  // `callback(saturated)` when the unary budget saturates and frees up again
  // (AdmissionBudget::OnSaturationChange).
  void OnSaturationChange(std::function<void(bool)> callback) {
    shared_.unary_in_flight.OnSaturationChange(std::move(callback));
  }

 private:
  using UnaryWork = std::function<grpc::Status(RequestLog& log)>;
  // Work that can answer only if it need not block: nullopt means "not now".
  using InlineWork = std::function<std::optional<grpc::Status>(RequestLog& log)>;

  // Finishes the call with `access` when it is not OK (ServiceContext::Authorize);
  // else admits the call at `cost` (request_cost.h; or sheds it with
  // RESOURCE_EXHAUSTED), runs `work` on the request pool unless the client has
  // gone, logs and finishes the call.
  grpc::ServerUnaryReactor* RunUnary(grpc::CallbackServerContext* context, const char* method,
                                     const grpc::Status& access, int64_t cost, UnaryWork work);
  // As RunUnary, but first tries `quick` on gRPC's own thread, and hands the
  // call to the request pool (`work`) only when `quick` returns nullopt. A
  // warm query is a copy of tens of microseconds; the hop to the pool and
  // back costs more than that in context switches. `quick` is called as
  // InlineWork, `work` as UnaryWork, but neither is made a std::function
  // (nor the log a shared object) unless the call goes to the pool: each
  // was an allocation a warm call.
  template <typename Quick, typename Work>
  grpc::ServerUnaryReactor* RunUnaryInlineFirst(grpc::CallbackServerContext* context,
                                                const char* method, const grpc::Status& access,
                                                int64_t cost, Quick quick, Work work);
  // RunUnaryInlineFirst's second half: `work` on the request pool, then the
  // log, the release of the admission and the end of the call.
  void RunOnPool(grpc::CallbackServerContext* context, grpc::ServerUnaryReactor* reactor,
                 RequestLog log, std::string client, int64_t cost, UnaryWork work);

  // A GetPoints call: its request, parsed from the raw bytes, and its world,
  // resolved once for both the admission's cost and the answer.
  struct GetPointsCall {
    v1::GetPointsRequest request;
    grpc::Status world_status;  // of resolving the request's world
    ResolvedWorld world;        // when world_status is OK
  };

  // GetPoints' answer, serialized into `response`; with may_block false,
  // nullopt when the rectangle's regions are not all cached (nothing is
  // generated or waited on then). With may_block, generation stops early
  // once `stop` returns true.
  std::optional<grpc::Status> AnswerGetPoints(const GetPointsCall& call, grpc::ByteBuffer& response,
                                              RequestLog& log, bool may_block,
                                              const std::function<bool()>& stop = nullptr);

  ServiceContext shared_;
};

template <typename Quick, typename Work>
grpc::ServerUnaryReactor* ScallopService::RunUnaryInlineFirst(grpc::CallbackServerContext* context,
                                                              const char* method,
                                                              const grpc::Status& access,
                                                              int64_t cost, Quick quick,
                                                              Work work) {
  grpc::ServerUnaryReactor* reactor = context->DefaultReactor();
  RequestLog log(method, shared_.metrics);
  if (!access.ok()) {
    log.Finish(access);
    reactor->Finish(access);
    return reactor;
  }
  std::string client;
  if (grpc::Status status = shared_.Admit(*context, shared_.unary_in_flight, cost, client);
      !status.ok()) {
    log.Finish(status);
    reactor->Finish(status);
    return reactor;
  }
  if (std::optional<grpc::Status> status = quick(log)) {
    log.Finish(*status);
    shared_.unary_in_flight.Release(client, cost);
    reactor->Finish(*status);
    return reactor;
  }
  RunOnPool(context, reactor, std::move(log), std::move(client), cost, UnaryWork(std::move(work)));
  return reactor;
}

}  // namespace scallop::server
