// GetPoints: one page of a rectangle's points, as packed arrays, with a
// tamper-evident token for the next page.
#include <algorithm>

#include "query_limits.h"
#include "scallop_service.h"
#include "status_mapping.h"
#include "world_messages.h"

namespace scallop::server {

grpc::ServerUnaryReactor* ScallopService::GetPoints(grpc::CallbackServerContext* context,
                                                    const v1::GetPointsRequest* request,
                                                    v1::GetPointsResponse* response) {
  return RunUnary(context, "GetPoints", [this, request, response](RequestLog& log) {
    World world;
    Rect rect;
    if (grpc::Status status = ResolveQuery(*request, config_.max_query_area, "max_query_area", log,
                                           world, rect);
        !status.ok()) {
      return status;
    }
    if (request->page_size() < 0) {
      return grpc::Status(grpc::StatusCode::INVALID_ARGUMENT,
                          "page_size: must be >= 0 (0 means max_page_size, " +
                              std::to_string(config_.max_page_size) + ")");
    }
    const size_t page_size = request->page_size() == 0
                                 ? config_.max_page_size
                                 : std::min(request->page_size(), config_.max_page_size);
    uint64_t offset = 0;
    if (!request->page_token().empty()) {
      StatusOr<uint64_t> decoded = page_tokens_.Decode(request->page_token(), world, rect);
      if (!decoded.ok()) return ToGrpcStatus(decoded.status());
      offset = *decoded;
    }
    // The whole rectangle on every page: its regions are cached after the
    // first page, so later pages cost a copy, and the order is the same.
    StatusOr<PlanePoints> points = engine_.Points(world, rect);
    if (!points.ok()) return ToGrpcStatus(points.status());
    const size_t total = points->ids.size();
    if (offset > total) {
      return grpc::Status(grpc::StatusCode::INVALID_ARGUMENT,
                          "page_token: points beyond the end of the rectangle");
    }
    const size_t end = std::min(total, static_cast<size_t>(offset) + page_size);
    AppendPoints(*points, offset, end, *response->mutable_points());
    if (end < total) response->set_next_page_token(page_tokens_.Encode(world, rect, end));
    *response->mutable_world() = WorldToMessage(world);
    log.add_points(static_cast<int64_t>(end - offset));
    return grpc::Status::OK;
  });
}

}  // namespace scallop::server
