// Routing of scallopd's HTTP requests, their errors, the world list and the
// viewer's files. The tiles themselves are in http_tiles.cc.
#include "server/http_api.h"

#include <boost/beast/http.hpp>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "scallop/plane/world_layers.h"
#include "server/call_authorization.h"
#include "server/tile_address.h"
#include "server/tile_encoding.h"
#include "server/viewer_assets.h"
#include "status_code_name.h"

namespace scallop::server {

namespace http = boost::beast::http;

int HttpStatusOf(grpc::StatusCode code) {
  switch (code) {
    case grpc::StatusCode::OK:
      return 200;
    case grpc::StatusCode::INVALID_ARGUMENT:
    case grpc::StatusCode::OUT_OF_RANGE:
    case grpc::StatusCode::FAILED_PRECONDITION:
      return 400;
    case grpc::StatusCode::UNAUTHENTICATED:
      return 401;
    case grpc::StatusCode::PERMISSION_DENIED:
      return 403;
    case grpc::StatusCode::NOT_FOUND:
      return 404;
    case grpc::StatusCode::ALREADY_EXISTS:
    case grpc::StatusCode::ABORTED:
      return 409;
    case grpc::StatusCode::RESOURCE_EXHAUSTED:
      return 429;
    case grpc::StatusCode::CANCELLED:
      return 499;
    case grpc::StatusCode::UNIMPLEMENTED:
      return 501;
    case grpc::StatusCode::UNAVAILABLE:
      return 503;
    case grpc::StatusCode::DEADLINE_EXCEEDED:
      return 504;
    default:
      return 500;
  }
}

HttpListener::Response HttpErrorResponse(const grpc::Status& status) {
  HttpListener::Response response;
  response.result(static_cast<unsigned>(HttpStatusOf(status.error_code())));
  response.set(http::field::content_type, "application/json");
  // Errors may change with the configuration or the load: never cached.
  response.set(http::field::cache_control, "no-store");
  if (status.error_code() == grpc::StatusCode::RESOURCE_EXHAUSTED) {
    response.set(http::field::retry_after, "1");
  }
  if (status.error_code() == grpc::StatusCode::UNAUTHENTICATED) {
    response.set(http::field::www_authenticate, "Bearer");
  }
  response.body() = nlohmann::json{{"error",
                                    {{"code", HttpStatusOf(status.error_code())},
                                     {"status", StatusCodeName(status.error_code())},
                                     {"message", status.error_message()}}}}
                        .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) +
                    "\n";
  return response;
}

std::optional<std::string_view> AuthorizationOf(const HttpListener::Request& request) {
  const auto header = request.find(http::field::authorization);
  if (header == request.end()) return std::nullopt;
  return AsStdText(header->value());
}

grpc::Status AuthorizeHttp(const ServiceContext& shared, const HttpListener::Request& request,
                           const RequestedWorld& world) {
  const std::optional<std::string_view> authorization = AuthorizationOf(request);
  return AuthorizeBearer(shared.tokens, authorization ? &*authorization : nullptr, world);
}

void HttpApi::Handle(const HttpListener::Request& request, const std::string& peer,
                     const HttpListener::Respond& respond) {
  const std::string_view target = AsStdText(request.target());
  const std::string_view path = target.substr(0, target.find('?'));
  if (request.method() != http::verb::get && request.method() != http::verb::head) {
    HttpListener::Response response = HttpErrorResponse(
        {grpc::StatusCode::UNIMPLEMENTED, "method: only GET and HEAD are served"});
    response.result(http::status::method_not_allowed);
    response.set(http::field::allow, "GET, HEAD");
    respond(std::move(response));
    return;
  }
  if (IsTileTarget(target)) {
    AnswerTile(request, peer, respond);
    return;
  }
  if (path == "/v1/worlds") {
    respond(AnswerWorldList(request));
    return;
  }
  if (const ViewerAsset* asset = FindViewerAsset(path)) {
    HttpListener::Response response;
    response.set(http::field::etag, AsBeastText(asset->etag));
    // Served by the binary: revalidated each time, so a new scallopd's page
    // is seen at once; the ETag makes that a 304.
    response.set(http::field::cache_control, "no-cache");
    if (AsStdText(request[http::field::if_none_match]) == asset->etag) {
      response.result(http::status::not_modified);
    } else {
      response.result(http::status::ok);
      response.set(http::field::content_type, AsBeastText(asset->content_type));
      response.body() = std::string(asset->bytes);
    }
    respond(std::move(response));
    return;
  }
  respond(HttpErrorResponse(
      {grpc::StatusCode::NOT_FOUND,
       "path: not found; scallopd serves /, /v1/worlds and /v1/worlds/{world}/tiles/{i}/{j}"}));
}

HttpListener::Response HttpApi::AnswerWorldList(const HttpListener::Request& request) {
  RequestLog log("HttpWorlds", shared_.metrics);
  const grpc::Status access = AuthorizeHttp(shared_, request, {});
  if (!access.ok()) {
    log.Finish(access);
    return HttpErrorResponse(access);
  }
  // Largest level whose tile area, 256 * 4^level d^2, is within max_query_area.
  int max_level = -1;
  while (max_level < kMaxTileLevel &&
         256.0 * std::ldexp(1.0, 2 * (max_level + 1)) <= shared_.config.max_query_area) {
    ++max_level;
  }
  nlohmann::json worlds = nlohmann::json::array();
  for (const std::string& name : shared_.worlds.names()) {
    // A token limited to some worlds lists only those.
    if (!AuthorizeHttp(shared_, request, {.kind = RequestedWorld::Kind::kNamed, .name = name})
             .ok()) {
      continue;
    }
    v1::DescribeWorldRequest by_name;
    by_name.set_world_name(name);
    ResolvedWorld resolved;
    if (!shared_.worlds.Resolve(by_name, resolved).ok()) continue;
    const World& world = resolved.world;
    const RegionLayout layout(world);
    worlds.push_back({{"name", name},
                      {"seed", std::to_string(world.seed())},
                      {"min_distance", world.min_distance()},
                      {"algorithm", std::string(WorldAlgorithmName(world.algorithm()))},
                      {"density", world.density()},
                      {"generator_version", world.generator_version()},
                      {"fingerprint", FingerprintHex(world.fingerprint())},
                      {"region_side", layout.side()},
                      {"precision_limit", layout.precision_limit()}});
    // A radius-field world's spacing range and kind (its tiles carry rs).
    if (const RadiusField* field = world.radius_field()) {
      worlds.back()["field_kind"] = std::string(RadiusFieldKindName(field->kind()));
      worlds.back()["r_min"] = field->r_min();
      worlds.back()["r_max"] = field->r_max();
    }
    // A layered world's layers, in the order tiles number them, each with its colour and
    // spacing range; its tiles carry each point's layer and spacing (format version 4).
    if (const WorldLayers* layers = world.layers()) {
      nlohmann::json list = nlohmann::json::array();
      for (int k = 0; k < layers->count(); ++k) {
        char colour[8];
        std::snprintf(colour, sizeof colour, "#%06x", TileLayerColour(k));
        list.push_back({{"name", layers->name(k)},
                        {"r_min", layers->world(k).min_distance()},
                        {"r_max", layers->world(k).max_spacing()},
                        {"colour", colour}});
      }
      worlds.back()["layers"] = list;
      worlds.back()["r_max"] = layers->largest_spacing();
      worlds.back()["tile_format_version"] = TileFormatVersion(world);
    }
  }
  HttpListener::Response response;
  response.result(http::status::ok);
  response.set(http::field::content_type, "application/json");
  // The configuration may change across restarts: always revalidated.
  response.set(http::field::cache_control, "no-cache");
  response.body() = nlohmann::json{{"default_world", shared_.worlds.default_name()},
                                   {"worlds", worlds},
                                   {"max_level", max_level},
                                   {"tile_format_version", kTileFormatVersion}}
                        .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) +
                    "\n";
  log.Finish(grpc::Status::OK);
  return response;
}

}  // namespace scallop::server
