// GetPoints: one page of a rectangle's points, as packed arrays (or encoded
// as the request asks, docs/wire.md), with a tamper-evident token for the
// next page. Answered on gRPC's thread when the rectangle's regions are all
// cached, on the request pool otherwise.
#include <algorithm>

#include "encoded_points.h"
#include "scallop/plane/layer_regions.h"
#include "server/layer_choice.h"
#include "server/region_warmup.h"
#include "server/request_cost.h"
#include "server/scallop_service.h"
#include "server/status_mapping.h"

namespace scallop::server {

grpc::ServerUnaryReactor* ScallopService::GetPoints(grpc::CallbackServerContext* context,
                                                    const v1::GetPointsRequest* request,
                                                    v1::GetPointsResponse* response) {
  return RunUnaryInlineFirst(
      context, "GetPoints", shared_.Authorize(*context, *request),
      RequestCost(shared_.worlds, *request),
      [this, request, response](RequestLog& log) {
        return AnswerGetPoints(*request, *response, log, /*may_block=*/false);
      },
      [this, context, request, response](RequestLog& log) {
        return *AnswerGetPoints(*request, *response, log, /*may_block=*/true,
                                StopWhenGone(context));
      });
}

std::optional<grpc::Status> ScallopService::AnswerGetPoints(const v1::GetPointsRequest& request,
                                                            v1::GetPointsResponse& response,
                                                            RequestLog& log, bool may_block,
                                                            const std::function<bool()>& stop) {
  World world;
  Rect rect;
  if (grpc::Status status = shared_.ResolveQuery(request, shared_.config.max_query_area,
                                                 "max_query_area", log, world, rect);
      !status.ok()) {
    return status;
  }
  if (request.page_size() < 0) {
    return grpc::Status(grpc::StatusCode::INVALID_ARGUMENT,
                        "page_size: must be >= 0 (0 means max_page_size, " +
                            std::to_string(shared_.config.max_page_size) + ")");
  }
  StatusOr<PointEncoding> encoding = PointEncodingFromMessage(request.encoding());
  if (!encoding.ok()) return ToGrpcStatus(encoding.status());
  LayerMask layers = kAllLayers;
  if (grpc::Status status = LayerFilterOf(world, request.layers(), "layers", layers);
      !status.ok()) {
    return status;
  }
  const size_t page_size = request.page_size() == 0
                               ? shared_.config.max_page_size
                               : std::min(request.page_size(), shared_.config.max_page_size);
  uint64_t offset = 0;
  if (!request.page_token().empty()) {
    StatusOr<uint64_t> decoded =
        shared_.page_tokens.Decode(request.page_token(), world, rect, layers);
    if (!decoded.ok()) return ToGrpcStatus(decoded.status());
    offset = *decoded;
  }
  // The whole rectangle on every page: its regions are cached after the
  // first page, so later pages cost a copy, and the order is the same. A
  // layered world's are each asked layer's, one layer after another.
  std::vector<LayerRegions> parts;
  if (may_block) {
    // Cold regions a block at a time, so a client that goes stops the work.
    if (grpc::Status status = WarmRegions(shared_.engine, world, rect, stop, layers); !status.ok())
      return status;
    StatusOr<std::vector<LayerRegions>> resolved =
        QueryRegions(shared_.engine, world, rect, layers);
    if (!resolved.ok()) return ToGrpcStatus(resolved.status());
    parts = std::move(*resolved);
  } else if (std::optional<std::vector<LayerRegions>> cached =
                 CachedQueryRegions(shared_.engine, world, rect, layers)) {
    parts = std::move(*cached);
  } else {
    return std::nullopt;
  }
  // Straight into the packed arrays (or the encoded regions), with room for
  // the page: one copy.
  size_t upper_bound = 0;
  for (const LayerRegions& part : parts) {
    for (const RegionHandle& region : part.regions) upper_bound += region->points.size();
  }
  v1::Points& points = *response.mutable_points();
  const size_t end = offset + page_size;
  size_t total = 0;
  WritePoints(points, *encoding, world, std::min(upper_bound, page_size), [&](auto& appender) {
    total = VisitLayerPoints(
        parts, rect, offset, end,
        [&](const LayerRegions& part) { appender.StartLayer(part.layer); },
        [&](const Vec2& position, uint64_t id) { appender.Append(position, id); });
  });
  if (offset > total) {
    response.clear_points();
    return grpc::Status(grpc::StatusCode::INVALID_ARGUMENT,
                        "page_token: points beyond the end of the rectangle");
  }
  if (end < total) {
    response.set_next_page_token(shared_.page_tokens.Encode(world, rect, end, layers));
  }
  *response.mutable_world() = shared_.worlds.ToMessage(world);
  log.add_points(static_cast<int64_t>(std::min(total, end) - std::min(total, offset)));
  return grpc::Status::OK;
}

}  // namespace scallop::server
