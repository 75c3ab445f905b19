// Building and serializing the null server's GetPoints responses.
#include "bench/null_server_responses.h"

#include <grpcpp/impl/codegen/proto_utils.h>

#include <stdexcept>

#include "bench/load_tile_plan.h"
#include "scallop/plane/plane_engine.h"
#include "scallop/v1/scallop.pb.h"
#include "world_messages.h"

namespace scallop::load {

std::vector<grpc::ByteBuffer> BuildNullResponses(const NullResponseOptions& options) {
  PlaneEngine engine({.cache_bytes = int64_t{64} << 20, .threads = 2});
  // The warm plan's placement over a square of 64 tiles a side: the same
  // spread of point counts as scallopd's answers for tiles of this size.
  const TilePlan plan({.mode = LoadMode::kWarm,
                       .tile_side = options.tile_side,
                       .warm_side = 64 * options.tile_side,
                       .run_seed = options.seed});
  std::vector<grpc::ByteBuffer> responses;
  for (int k = 0; k < options.count; ++k) {
    StatusOr<PlanePoints> points = engine.Points(options.world, plan.Tile(k));
    if (!points.ok()) throw std::runtime_error(points.status().message());
    v1::GetPointsResponse response;
    AppendPoints(*points, 0, points->ids.size(), *response.mutable_points());
    *response.mutable_world() = WorldToMessage(options.world);
    grpc::ByteBuffer buffer;
    bool own_buffer = false;
    const grpc::Status status =
        grpc::SerializationTraits<v1::GetPointsResponse>::Serialize(response, &buffer, &own_buffer);
    if (!status.ok()) throw std::runtime_error(status.error_message());
    responses.push_back(std::move(buffer));
  }
  return responses;
}

}  // namespace scallop::load
