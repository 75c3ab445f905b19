// The scallop.v1.Scallop service on gRPC's callback API: no thread per
// request. Handlers hand each call to the request pool, which validates and
// answers it; the engine generates regions on its own pool and shares one
// region cache among all requests, so a region is generated once however many
// requests want it at once. Each RPC's body lives in its own file.
#pragma once

#include <boost/asio/thread_pool.hpp>
#include <functional>
#include <optional>

#include "in_flight_limit.h"
#include "page_token.h"
#include "request_log.h"
#include "scallop/noise/nearest_lookup.h"
#include "scallop/plane/plane_engine.h"
#include "scallop/plane/query_rect.h"
#include "scallop/v1/scallop.grpc.pb.h"
#include "server_config.h"
#include "status_mapping.h"
#include "world_messages.h"
#include "world_registry.h"

namespace scallop::server {

class ScallopService final : public v1::Scallop::CallbackService {
 public:
  // All references must outlive the service; the pool must outlive every call.
  // `metrics` (may be null: not recorded) counts every finished call.
  ScallopService(const ServerConfig& config, const WorldRegistry& worlds,
                 const PageTokenCodec& page_tokens, PlaneEngine& engine,
                 boost::asio::thread_pool& request_pool, RequestMetrics* metrics = nullptr);

  grpc::ServerUnaryReactor* GetPoints(grpc::CallbackServerContext* context,
                                      const v1::GetPointsRequest* request,
                                      v1::GetPointsResponse* response) override;
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
  int requests_in_flight() const { return in_flight_.in_flight() + streams_in_flight_.in_flight(); }

 private:
  friend class StreamPointsReactor;
  friend class FollowReactor;
  using UnaryWork = std::function<grpc::Status(RequestLog& log)>;
  // Work that can answer only if it need not block: nullopt means "not now".
  using InlineWork = std::function<std::optional<grpc::Status>(RequestLog& log)>;

  // Admits the call (or sheds it with RESOURCE_EXHAUSTED), runs `work` on the
  // request pool unless the client has gone, logs and finishes the call.
  grpc::ServerUnaryReactor* RunUnary(grpc::CallbackServerContext* context, const char* method,
                                     UnaryWork work);
  // As RunUnary, but first tries `quick` on gRPC's own thread, and hands the
  // call to the request pool (`work`) only when `quick` returns nullopt. A
  // warm query is a copy of tens of microseconds; the hop to the pool and
  // back costs more than that in context switches.
  grpc::ServerUnaryReactor* RunUnaryInlineFirst(grpc::CallbackServerContext* context,
                                                const char* method, InlineWork quick,
                                                UnaryWork work);

  // GetPoints' answer; with may_block false, nullopt when the rectangle's
  // regions are not all cached (nothing is generated or waited on then).
  // With may_block, generation stops early once `stop` returns true.
  std::optional<grpc::Status> AnswerGetPoints(const v1::GetPointsRequest& request,
                                              v1::GetPointsResponse& response, RequestLog& log,
                                              bool may_block,
                                              const std::function<bool()>& stop = nullptr);

  // INVALID_ARGUMENT naming `field` when a Nearest or NoiseGrid call's
  // positions lie in more than max_nearest_regions distinct regions (what
  // their cost grows with); `advice` says how to stay within it.
  grpc::Status CheckNearestRegions(int64_t regions, const char* field, const char* advice) const;

  // True once the call's client has cancelled or its deadline has passed:
  // what long work polls so that it stops for a client that has gone.
  static std::function<bool()> StopWhenGone(grpc::CallbackServerContext* context) {
    return [context] { return context->IsCancelled(); };
  }

  // The world and rectangle a query names, resolved, logged and checked
  // against `max_area` (named `limit_name` in errors): the prelude of every
  // RPC that reads a rectangle.
  template <typename Request>
  grpc::Status ResolveQuery(const Request& request, double max_area, const char* limit_name,
                            RequestLog& log, World& world, Rect& rect) const {
    ResolvedWorld resolved;
    if (grpc::Status status = worlds_.Resolve(request, resolved); !status.ok()) return status;
    world = resolved.world;
    log.set_world(world.Describe());
    rect = RectFromMessage(request.rect());
    log.set_rect(rect);
    if (!request.has_rect()) {
      return {grpc::StatusCode::INVALID_ARGUMENT,
              "rect: required, the half-open rectangle [x0, x1) x [y0, y1)"};
    }
    return ToGrpcStatus(CheckQueryRect(world, rect, {.max_area = max_area, .name = limit_name}));
  }

  const ServerConfig& config_;
  const WorldRegistry& worlds_;
  const PageTokenCodec& page_tokens_;
  PlaneEngine& engine_;
  // Nearest and NoiseGrid: search grids cached across requests, on engine_'s regions.
  NearestLookup nearest_lookup_{engine_};
  boost::asio::thread_pool& request_pool_;
  RequestMetrics* metrics_;
  InFlightLimit in_flight_;          // unary calls (max_in_flight)
  InFlightLimit streams_in_flight_;  // StreamPoints and Follow (max_streams_in_flight)
};

}  // namespace scallop::server
