// Nearest: the cellular-noise basis (nearest id and position, F1, F2, cell
// value) at a batch of positions, as packed arrays in the request's order.
// Cost follows the distinct regions the positions lie in, so that is what
// is bounded (max_nearest_regions), before any work.
#include <string>
#include <vector>

#include "scallop/plane/layer_regions.h"
#include "server/layer_choice.h"
#include "server/request_cost.h"
#include "server/scallop_service.h"
#include "server/status_mapping.h"
#include "world_messages.h"

namespace scallop::server {

grpc::ServerUnaryReactor* ScallopService::Nearest(grpc::CallbackServerContext* context,
                                                  const v1::NearestRequest* request,
                                                  v1::NearestResponse* response) {
  const grpc::Status auth = shared_.Authorize(*context, *request);
  return RunUnary(
      context, "Nearest", auth,
      RequestCost(shared_.worlds, *request, shared_.config.max_nearest_regions),
      [this, context, request, response](RequestLog& log) {
        World asked;
        if (grpc::Status status = shared_.ResolveWorld(*request, log, asked); !status.ok())
          return status;
        // A layered world answers for the layer named: that layer's world, its points and ids.
        int layer = -1;
        if (grpc::Status status = LayerChoiceOf(asked, request->layer(), "layer", layer);
            !status.ok()) {
          return status;
        }
        const World& world = WorldOfLayer(asked, layer);
        const v1::Positions& message = request->positions();
        if (message.xs_size() != message.ys_size()) {
          return grpc::Status(grpc::StatusCode::INVALID_ARGUMENT,
                              "positions: xs has " + std::to_string(message.xs_size()) +
                                  " entries and ys " + std::to_string(message.ys_size()) +
                                  "; they must have the same length");
        }
        if (message.xs_size() > shared_.config.max_nearest_batch) {
          return grpc::Status(
              grpc::StatusCode::INVALID_ARGUMENT,
              "positions: " + std::to_string(message.xs_size()) + " positions, at most " +
                  std::to_string(shared_.config.max_nearest_batch) + " (max_nearest_batch)");
        }
        std::vector<Vec2> positions(message.xs_size());
        for (int k = 0; k < message.xs_size(); ++k) {
          positions[k] = {message.xs(k), message.ys(k)};
          if (Status status = NearestLookup::ValidatePosition(world, positions[k], k);
              !status.ok()) {
            return ToGrpcStatus(status);
          }
        }
        if (grpc::Status status = shared_.CheckNearestRegions(
                world, NearestLookup::CountRegions(world, positions), "positions",
                "split scattered positions into several calls");
            !status.ok()) {
          return status;
        }
        std::vector<NearestPoint> results(positions.size());
        if (Status status =
                shared_.nearest_lookup.Nearest(world, positions, results, StopWhenGone(context));
            !status.ok()) {
          return ToGrpcStatus(status);
        }
        *response->mutable_world() = shared_.worlds.ToMessage(asked);
        const int count = static_cast<int>(results.size());
        for (auto* field :
             {response->mutable_f1(), response->mutable_f2(), response->mutable_nearest_xs(),
              response->mutable_nearest_ys(), response->mutable_cell_values()}) {
          field->Reserve(count);
        }
        response->mutable_ids()->Reserve(count);
        for (const NearestPoint& n : results) {
          response->add_ids(n.id);
          response->add_f1(n.f1);
          response->add_f2(n.f2);
          response->add_nearest_xs(n.position.x);
          response->add_nearest_ys(n.position.y);
          response->add_cell_values(n.cell_value);
        }
        log.add_points(count);
        return grpc::Status::OK;
      });
}

}  // namespace scallop::server
