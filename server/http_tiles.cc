// GET /v1/worlds/{world}/tiles/{i}/{j}: a tile's points, cacheable for ever
// (worlds are immutable). Answered on the listener's thread when its regions
// are cached, on the request pool otherwise.
#include <boost/asio/post.hpp>
#include <boost/beast/http.hpp>

#include "scallop/plane/layer_regions.h"
#include "scallop/plane/query_rect.h"
#include "scallop/plane/world_layers.h"
#include "server/client_key.h"
#include "server/http_api.h"
#include "server/region_warmup.h"
#include "server/request_cost.h"
#include "server/tile_encoding.h"

namespace scallop::server {
namespace {

namespace http = boost::beast::http;

// A cold tile not made by then is given up (504): the client has likely
// gone, and nothing else stops the work for it.
constexpr auto kColdTileTimeout = std::chrono::seconds(30);

// True when an If-None-Match list holds `etag` (or is "*"); weak tags match
// too, as RFC 9110 asks of If-None-Match.
bool NoneMatchHolds(std::string_view header, std::string_view etag) {
  for (size_t start = 0; start < header.size();) {
    size_t end = header.find(',', start);
    if (end == std::string_view::npos) end = header.size();
    std::string_view tag = header.substr(start, end - start);
    while (!tag.empty() && tag.front() == ' ') tag.remove_prefix(1);
    while (!tag.empty() && tag.back() == ' ') tag.remove_suffix(1);
    if (tag.starts_with("W/")) tag.remove_prefix(2);
    if (tag == etag || tag == "*") return true;
    start = end + 1;
  }
  return false;
}

// The tile's points from its regions (each layer's, for a layered world):
// those in the rectangle, and for PNG also those within the margin beyond it
// (drawn across the edge).
Tile CollectTile(const std::vector<LayerRegions>& parts, const Rect& reach, Tile tile) {
  const bool layered = tile.world.layers() != nullptr;
  const World* spacing = tile.world.radius_field() != nullptr ? &tile.world : nullptr;
  int layer = -1;
  VisitLayerPoints(
      parts, reach, 0, std::numeric_limits<size_t>::max(),
      [&](const LayerRegions& part) {
        layer = part.layer;
        if (layered) spacing = &part.world;
      },
      [&](const Vec2& position, uint64_t id) {
        tile.ids.push_back(id);
        tile.xs.push_back(position.x);
        tile.ys.push_back(position.y);
        // R is a pure function of the field: these are the bits the point was
        // placed with, as GetPoints' radii carry them; a layered world's
        // points carry their layer's spacing, so disks are drawn to scale.
        if (spacing != nullptr) tile.rs.push_back(spacing->SpacingAt(position));
        if (layered) tile.layers.push_back(static_cast<uint16_t>(layer));
      });
  if (const WorldLayers* layers = tile.world.layers()) {
    for (int k = 0; k < layers->count(); ++k) tile.layer_names.push_back(layers->name(k));
  }
  return tile;
}

}  // namespace

void HttpApi::AnswerTile(const HttpListener::Request& request, const std::string& peer,
                         const HttpListener::Respond& respond) {
  auto log = std::make_shared<RequestLog>("HttpTile", shared_.metrics);
  auto fail = [&](const grpc::Status& status) {
    log->Finish(status);
    respond(HttpErrorResponse(status));
  };
  const std::string_view target = AsStdText(request.target());
  const std::string_view accept = AsStdText(request[http::field::accept]);
  StatusOr<TileAddress> parsed = ParseTileAddress(target, accept);
  if (!parsed.ok()) return fail(ToGrpcStatus(parsed.status()));
  const TileAddress address = std::move(*parsed);

  if (grpc::Status access = AuthorizeHttp(
          shared_, request, {.kind = RequestedWorld::Kind::kNamed, .name = address.world});
      !access.ok()) {
    return fail(access);
  }
  v1::DescribeWorldRequest by_name;
  by_name.set_world_name(address.world);
  ResolvedWorld resolved;
  if (grpc::Status status = shared_.worlds.Resolve(by_name, resolved); !status.ok()) {
    return fail(status);
  }
  const RegionLayout layout(resolved.world);
  Tile tile{.world_name = address.world,
            .world = resolved.world,
            .key = address.key,
            .rect = TileRect(layout, address.key),
            .ids = {},
            .xs = {},
            .ys = {},
            .rs = {},
            .layers = {},
            .layer_names = {}};
  log->set_world(tile.world, resolved.description);
  log->set_rect(tile.rect);
  if (Status status = CheckQueryRect(
          tile.world, tile.rect,
          {.max_area = shared_.config.max_query_area, .name = "max_query_area"}, "tile");
      !status.ok()) {
    return fail(ToGrpcStatus(status));
  }

  // Headers shared by the 200 and the 304 (RFC 9110: a 304 repeats them).
  HttpListener::Response response;
  const std::string etag = TileEtag(tile.world, address.key, address.format);
  response.set(http::field::etag, etag);
  // With tokens, a shared cache must not hand a tile to callers without one.
  response.set(http::field::cache_control,
               std::string(shared_.tokens ? "private" : "public") + ", max-age=" +
                   std::to_string(shared_.config.http_max_age_seconds) + ", immutable");
  if (!address.format_in_url) response.set(http::field::vary, "Accept");
  if (!shared_.tokens) response.set(http::field::access_control_allow_origin, "*");
  const auto none_match = request.find(http::field::if_none_match);
  if (none_match != request.end() && NoneMatchHolds(AsStdText(none_match->value()), etag)) {
    response.result(http::status::not_modified);
    log->Finish(grpc::Status::OK);
    respond(std::move(response));
    return;
  }
  // The PNG draws points up to its margin beyond the tile, within the
  // precision range (growing past it would refuse the edge tiles).
  Rect reach = tile.rect;
  if (address.format == TileFormat::kPng) {
    const double margin = TilePngMargin(tile);
    const double limit = layout.precision_limit();
    reach = {std::max(-limit, reach.x0 - margin), std::max(-limit, reach.y0 - margin),
             std::min(limit, reach.x1 + margin), std::min(limit, reach.y1 + margin)};
  }
  // Admitted as a GetPoints of the same regions is: the same budget, cost,
  // client share and rate limit.
  const std::optional<std::string_view> authorization = AuthorizationOf(request);
  const std::string client =
      ClientKey(authorization ? &*authorization : nullptr, peer, shared_.tokens != nullptr);
  const int64_t cost = RegionsCost(tile.world, reach);
  double retry_after = 0;
  if (grpc::Status admitted = shared_.Admit(client, shared_.unary_in_flight, cost, &retry_after);
      !admitted.ok()) {
    log->Finish(admitted);
    HttpListener::Response refusal = HttpErrorResponse(admitted);
    if (retry_after > 0) {
      refusal.set(http::field::retry_after,
                  std::to_string(static_cast<int64_t>(std::ceil(retry_after))));
    }
    respond(std::move(refusal));
    return;
  }
  response.result(http::status::ok);
  response.set(http::field::content_type, AsBeastText(TileContentType(address.format)));
  // Encodes and answers; on whichever thread has the regions.
  auto finish = [this, log, reach, client, cost, format = address.format](
                    const std::vector<LayerRegions>& regions, Tile tile,
                    HttpListener::Response response, const HttpListener::Respond& respond) {
    tile = CollectTile(regions, reach, std::move(tile));
    log->add_points(static_cast<int64_t>(tile.ids.size()));
    if (format == TileFormat::kPng) {
      StatusOr<std::string> png = RenderTilePng(tile);
      if (!png.ok()) {
        shared_.unary_in_flight.Release(client, cost);
        log->Finish(ToGrpcStatus(png.status()));
        respond(HttpErrorResponse(ToGrpcStatus(png.status())));
        return;
      }
      response.body() = std::move(*png);
    } else {
      response.body() = format == TileFormat::kJson ? EncodeTileJson(tile) : EncodeTileBinary(tile);
    }
    shared_.unary_in_flight.Release(client, cost);
    log->Finish(grpc::Status::OK);
    respond(std::move(response));
  };
  if (std::optional<std::vector<LayerRegions>> cached =
          CachedQueryRegions(shared_.engine, tile.world, reach)) {
    finish(*cached, std::move(tile), std::move(response), respond);
    return;
  }
  boost::asio::post(
      shared_.request_pool, [this, log, reach, client, cost, tile = std::move(tile),
                             response = std::move(response), respond, finish]() mutable {
        const auto deadline = std::chrono::steady_clock::now() + kColdTileTimeout;
        grpc::Status status = WarmRegions(shared_.engine, tile.world, reach, [deadline] {
          return std::chrono::steady_clock::now() > deadline;
        });
        if (status.error_code() == grpc::StatusCode::CANCELLED) {
          status = {grpc::StatusCode::DEADLINE_EXCEEDED, "tile: not generated within 30 s"};
        }
        std::vector<LayerRegions> regions;
        if (status.ok()) {
          StatusOr<std::vector<LayerRegions>> resolved =
              QueryRegions(shared_.engine, tile.world, reach);
          if (resolved.ok()) {
            regions = std::move(*resolved);
          } else {
            status = ToGrpcStatus(resolved.status());
          }
        }
        if (!status.ok()) {
          shared_.unary_in_flight.Release(client, cost);
          log->Finish(status);
          respond(HttpErrorResponse(status));
          return;
        }
        finish(regions, std::move(tile), std::move(response), respond);
      });
}

}  // namespace scallop::server
