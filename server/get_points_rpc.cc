// GetPoints: one page of a rectangle's points, as packed arrays (or encoded
// as the request asks, docs/wire.md), with a tamper-evident token for the
// next page. Answered on gRPC's thread when the rectangle's regions are all
// cached, on the request pool otherwise.
#include <grpcpp/impl/codegen/proto_utils.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>

#include "encoded_points.h"
#include "scallop/plane/layer_regions.h"
#include "server/layer_choice.h"
#include "server/packed_answer.h"
#include "server/region_warmup.h"
#include "server/request_cost.h"
#include "server/scallop_service.h"
#include "server/status_mapping.h"

namespace scallop::server {

grpc::ServerUnaryReactor* ScallopService::GetPoints(grpc::CallbackServerContext* context,
                                                    const grpc::ByteBuffer* request_bytes,
                                                    grpc::ByteBuffer* response) {
  // Parsed as gRPC parses a typed method's request (an unparsable one ends
  // with its status); kept with the world until the call ends.
  auto call = std::make_shared<GetPointsCall>();
  grpc::ByteBuffer bytes = *request_bytes;  // shares the slices; Deserialize consumes it
  grpc::Status access =
      grpc::SerializationTraits<v1::GetPointsRequest>::Deserialize(&bytes, &call->request);
  int64_t cost = 1;  // a request the call will refuse costs nothing (request_cost.h)
  if (access.ok()) access = shared_.Authorize(*context, call->request);
  if (access.ok()) {
    call->world_status = shared_.worlds.Resolve(call->request, call->world);
    if (call->world_status.ok()) {
      cost = RegionsCost(call->world.world, RectFromMessage(call->request.rect()));
    }
  }
  return RunUnaryInlineFirst(
      context, "GetPoints", access, cost,
      [this, &call = *call, response](RequestLog& log) {
        return AnswerGetPoints(call, *response, log, /*may_block=*/false);
      },
      [this, context, call, response](RequestLog& log) {
        return *AnswerGetPoints(*call, *response, log, /*may_block=*/true, StopWhenGone(context));
      });
}

std::optional<grpc::Status> ScallopService::AnswerGetPoints(const GetPointsCall& call,
                                                            grpc::ByteBuffer& response,
                                                            RequestLog& log, bool may_block,
                                                            const std::function<bool()>& stop) {
  if (!call.world_status.ok()) return call.world_status;
  const v1::GetPointsRequest& request = call.request;
  const World& world = call.world.world;
  log.set_world(world, call.world.description);
  Rect rect;
  if (grpc::Status status = shared_.CheckQuery(request, world, shared_.config.max_query_area,
                                               "max_query_area", log, rect);
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
  // Straight into the answer's bytes (the common case: packed, neither radii
  // nor layers) or into the message's arrays or encoded regions, with room
  // for the page: one copy.
  size_t upper_bound = 0;
  for (const LayerRegions& part : parts) {
    for (const RegionHandle& region : part.regions) upper_bound += region->points.size();
  }
  const size_t end = offset + page_size;
  const size_t capacity = std::min(upper_bound, page_size);
  size_t total = 0;
  auto fill = [&](auto& appender) {
    total = VisitLayerPoints(
        parts, rect, offset, end,
        [&](const LayerRegions& part) { appender.StartLayer(part.layer); },
        AppendTo<std::remove_reference_t<decltype(appender)>>{appender});
  };
  std::optional<PackedAnswerWriter> packed;
  v1::GetPointsResponse message;
  if (*encoding == PointEncoding::kPacked && world.radius_field() == nullptr &&
      world.layers() == nullptr) {
    fill(packed.emplace(capacity));
  } else {
    WritePoints(*message.mutable_points(), *encoding, world, capacity, fill);
  }
  if (offset > total) {
    return grpc::Status(grpc::StatusCode::INVALID_ARGUMENT,
                        "page_token: points beyond the end of the rectangle");
  }
  const std::string next_page_token =
      end < total ? shared_.page_tokens.Encode(world, rect, end, layers) : std::string();
  log.add_points(static_cast<int64_t>(std::min(total, end) - std::min(total, offset)));
  if (packed) {
    response =
        call.world.message != nullptr
            ? packed->Finish(next_page_token, *call.world.message)
            : packed->Finish(next_page_token, shared_.worlds.ToMessage(world).SerializeAsString());
    return grpc::Status::OK;
  }
  message.set_next_page_token(next_page_token);
  *message.mutable_world() = shared_.worlds.ToMessage(world);
  bool own_buffer = false;
  return grpc::SerializationTraits<v1::GetPointsResponse>::Serialize(message, &response,
                                                                     &own_buffer);
}

}  // namespace scallop::server
