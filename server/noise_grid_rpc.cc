// NoiseGrid: one channel of the cellular-noise basis on a regular grid of
// samples, row-major, as scallop/noise/noise_grid.h evaluates it. Its cost
// follows the regions the samples lie in (max_nearest_regions, checked first).
#include <optional>

#include "noise_messages.h"
#include "scallop/noise/noise_grid.h"
#include "scallop/plane/layer_regions.h"
#include "server/layer_choice.h"
#include "server/request_cost.h"
#include "server/scallop_service.h"
#include "server/status_mapping.h"
#include "world_messages.h"

namespace scallop::server {

grpc::ServerUnaryReactor* ScallopService::NoiseGrid(grpc::CallbackServerContext* context,
                                                    const v1::NoiseGridRequest* request,
                                                    v1::NoiseGridResponse* response) {
  const grpc::Status auth = shared_.Authorize(*context, *request);
  return RunUnary(
      context, "NoiseGrid", auth,
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
        const std::optional<NoiseChannel> channel = NoiseChannelFromMessage(request->channel());
        if (!channel) {
          return grpc::Status(grpc::StatusCode::INVALID_ARGUMENT,
                              "channel: required, one of NOISE_CHANNEL_F1, _F2, _F2_MINUS_F1, _ID, "
                              "_CELL_VALUE");
        }
        const NoiseGridSpec spec{.origin = {request->origin_x(), request->origin_y()},
                                 .step = request->step(),
                                 .width = request->width(),
                                 .height = request->height(),
                                 .channel = *channel};
        if (Status status = ValidateNoiseGrid(world, spec, shared_.config.max_noise_grid_samples);
            !status.ok()) {
          // The core names the limit's value; say which setting it is.
          if (status.message().starts_with("width * height")) {
            status = {status.code(), status.message() + " (max_noise_grid_samples)"};
          }
          return ToGrpcStatus(status);
        }
        if (grpc::Status status = shared_.CheckNearestRegions(
                world, NoiseGridRegions(world, spec), "step: the samples",
                "use a smaller step or fewer samples");
            !status.ok()) {
          return status;
        }
        StatusOr<NoiseImage> image =
            EvaluateNoiseGrid(shared_.nearest_lookup, world, spec,
                              shared_.config.max_noise_grid_samples, StopWhenGone(context));
        if (!image.ok()) return ToGrpcStatus(image.status());
        *response->mutable_world() = shared_.worlds.ToMessage(asked);
        response->set_width(image->width);
        response->set_height(image->height);
        response->mutable_values()->Add(image->values.begin(), image->values.end());
        response->mutable_ids()->Add(image->ids.begin(), image->ids.end());
        log.add_points(int64_t{image->width} * image->height);
        return grpc::Status::OK;
      });
}

}  // namespace scallop::server
