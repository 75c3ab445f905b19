// scallopd's HTTP side (--http-listen): the web viewer at /, the world list
// at /v1/worlds and the cacheable tiles at /v1/worlds/{world}/tiles/{i}/{j}
// (docs/tiles.md). Calls share the gRPC service's ServiceContext: the same
// worlds, engine and region cache, tokens, admission slots (max_in_flight)
// and area limit (max_query_area), and are logged and counted as "HttpTile"
// and "HttpWorlds" the same way.
#pragma once

#include <string>

#include "server/http_listener.h"
#include "server/service_context.h"

namespace scallop::server {

class HttpApi {
 public:
  // `shared` must outlive the API and every answer still on its pool.
  explicit HttpApi(ServiceContext& shared) : shared_(shared) {}

  // The listener's handler: routes by method and path, never blocks (cold
  // tiles go to the request pool) and answers every request, errors as
  // JSON {"error": {"code", "status", "message"}}.
  void Handle(const HttpListener::Request& request, const HttpListener::Respond& respond);

 private:
  void AnswerTile(const HttpListener::Request& request, const HttpListener::Respond& respond);
  HttpListener::Response AnswerWorldList(const HttpListener::Request& request);

  ServiceContext& shared_;
};

// The HTTP status of a gRPC code, as Google's APIs map them: INVALID_ARGUMENT
// and OUT_OF_RANGE 400, UNAUTHENTICATED 401, PERMISSION_DENIED 403,
// NOT_FOUND 404, RESOURCE_EXHAUSTED 429, CANCELLED 499, INTERNAL 500,
// UNAVAILABLE 503, DEADLINE_EXCEEDED 504 (the rest in docs/tiles.md).
int HttpStatusOf(grpc::StatusCode code);

// An error answer: the status's HTTP code and a JSON body naming the gRPC
// code and the message; never cached (Cache-Control: no-store).
HttpListener::Response HttpErrorResponse(const grpc::Status& status);

// The request's "authorization" header checked like a gRPC call's metadata
// (call_authorization.h).
// The client an HTTP request counts as in the admission budget: its token's
// key when tokens are checked, else "http:anonymous" (the listener does not
// pass peer addresses yet), so anonymous tiles together hold at most
// max_client_share of the unary budget.
std::string HttpClientKey(const ServiceContext& shared, const HttpListener::Request& request);

grpc::Status AuthorizeHttp(const ServiceContext& shared, const HttpListener::Request& request,
                           const RequestedWorld& world);

}  // namespace scallop::server
