// ServiceContext: what every call of the Scallop service shares (its
// configuration, worlds, page tokens, engine, request pool, admission budgets
// and metrics), in one small object that each RPC's file reaches directly, so
// a streaming reactor needs no access to the service's private parts. The
// HTTP tiles (http_api.h) share it too.
#pragma once

#include <grpcpp/server_context.h>

#include <boost/asio/thread_pool.hpp>
#include <cstdint>
#include <functional>

#include "scallop/noise/nearest_lookup.h"
#include "scallop/plane/plane_engine.h"
#include "scallop/plane/query_rect.h"
#include "server/admission_budget.h"
#include "server/call_authorization.h"
#include "server/client_key.h"
#include "server/page_token.h"
#include "server/rate_limiter.h"
#include "server/request_log.h"
#include "server/server_config.h"
#include "server/status_mapping.h"
#include "server/world_registry.h"
#include "world_messages.h"

namespace scallop::server {

class ServiceContext {
 public:
  // All references must outlive the context; the pool must outlive every
  // call. `metrics` (may be null: not recorded) counts every finished call.
  // `tokens` (may be null: no token needed) must outlive it too.
  ServiceContext(const ServerConfig& config, const WorldRegistry& worlds,
                 const PageTokenCodec& page_tokens, PlaneEngine& engine,
                 boost::asio::thread_pool& request_pool, RequestMetrics* metrics,
                 const TokenTable* tokens)
      : config(config),
        worlds(worlds),
        page_tokens(page_tokens),
        engine(engine),
        request_pool(request_pool),
        metrics(metrics),
        tokens(tokens),
        unary_in_flight({.max_calls = config.max_in_flight,
                         .max_cost = config.max_in_flight_cost,
                         .client_share = config.max_client_share}),
        streams_in_flight({.max_calls = config.max_streams_in_flight,
                           .max_cost = config.max_streams_in_flight,
                           .client_share = config.max_client_share,
                           .calls_setting = "max_streams_in_flight",
                           .cost_setting = "max_streams_in_flight"}),
        rate_limiter(config.rate_limit_per_second, config.rate_limit_burst) {}
  ServiceContext(const ServiceContext&) = delete;
  ServiceContext& operator=(const ServiceContext&) = delete;

  // The call's token, and whether it may use the world `request` asks for
  // (call_authorization.h). Checked before admission, so callers without a
  // token take no slot and learn nothing of the load.
  template <typename Request>
  grpc::Status Authorize(const grpc::ServerContextBase& context, const Request& request) const {
    return AuthorizeCall(tokens, context, RequestedWorldOf(request, worlds.default_name()));
  }
  // The same for calls that concern no world (GetServerInfo, Follow's start).
  grpc::Status Authorize(const grpc::ServerContextBase& context) const {
    return AuthorizeCall(tokens, context, {});
  }

  // The world a request names, resolved and logged.
  template <typename Request>
  grpc::Status ResolveWorld(const Request& request, RequestLog& log, World& world) const {
    ResolvedWorld resolved;
    if (grpc::Status status = worlds.Resolve(request, resolved); !status.ok()) return status;
    world = resolved.world;
    log.set_world(world, resolved.description);
    return grpc::Status::OK;
  }

  // The world and rectangle a query names, resolved, logged and checked by
  // the rectangle rule against `max_area` (named `limit_name` in errors):
  // the prelude of every RPC that reads a rectangle.
  template <typename Request>
  grpc::Status ResolveQuery(const Request& request, double max_area, const char* limit_name,
                            RequestLog& log, World& world, Rect& rect) const {
    if (grpc::Status status = ResolveWorld(request, log, world); !status.ok()) return status;
    return CheckQuery(request, world, max_area, limit_name, log, rect);
  }
  // ResolveQuery's rectangle part, for a call whose world is resolved already.
  template <typename Request>
  grpc::Status CheckQuery(const Request& request, const World& world, double max_area,
                          const char* limit_name, RequestLog& log, Rect& rect) const {
    rect = RectFromMessage(request.rect());
    log.set_rect(rect);
    if (!request.has_rect()) {
      return {grpc::StatusCode::INVALID_ARGUMENT,
              "rect: required, the half-open rectangle [x0, x1) x [y0, y1)"};
    }
    return ToGrpcStatus(CheckQueryRect(world, rect, {.max_area = max_area, .name = limit_name}));
  }

  // Admits a call that passed Authorize: its client's rate limit
  // (RESOURCE_EXHAUSTED with a retry delay, retry_status.h), then room for
  // `cost` in `budget`. On OK the call holds `cost` under the key written to
  // `client` until budget.Release(client, cost).
  grpc::Status Admit(const grpc::ServerContextBase& context, AdmissionBudget& budget, int64_t cost,
                     std::string& client);
  // The same for a caller known by its client key (client_key.h), such as an
  // HTTP request; a refusal by the rate limiter writes its delay, in
  // seconds, to `retry_after` (when not null).
  grpc::Status Admit(const std::string& client, AdmissionBudget& budget, int64_t cost,
                     double* retry_after = nullptr);

  // INVALID_ARGUMENT naming `field` when a Nearest or NoiseGrid call's
  // positions lie in more than max_nearest_regions distinct regions (what
  // their cost grows with, regions of `world`'s layout); `advice` says how
  // to stay within it.
  grpc::Status CheckNearestRegions(const World& world, int64_t regions, const char* field,
                                   const char* advice) const;

  // Calls admitted and not yet finished (unary and streaming), for the metrics.
  int requests_in_flight() const {
    return unary_in_flight.in_flight() + streams_in_flight.in_flight();
  }

  const ServerConfig& config;
  const WorldRegistry& worlds;
  const PageTokenCodec& page_tokens;
  PlaneEngine& engine;
  boost::asio::thread_pool& request_pool;
  RequestMetrics* const metrics;
  const TokenTable* const tokens;
  // Nearest and NoiseGrid: search grids cached across requests, on engine's regions.
  NearestLookup nearest_lookup{engine};
  AdmissionBudget unary_in_flight;    // unary calls (max_in_flight, max_in_flight_cost)
  AdmissionBudget streams_in_flight;  // StreamPoints and Follow (max_streams_in_flight)
  RateLimiter rate_limiter;           // calls of every kind, per client
};

// True once the call's client has cancelled or its deadline has passed: what
// long work polls so that it stops for a client that has gone.
inline std::function<bool()> StopWhenGone(grpc::CallbackServerContext* context) {
  return [context] { return context->IsCancelled(); };
}

}  // namespace scallop::server
