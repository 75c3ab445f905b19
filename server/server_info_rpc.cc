// GetServerInfo: the generator version, the limits and the configured worlds.
#include "field_messages.h"
#include "scallop/plane/region_layout.h"
#include "server/scallop_service.h"

namespace scallop::server {

grpc::ServerUnaryReactor* ScallopService::GetServerInfo(grpc::CallbackServerContext* context,
                                                        const v1::GetServerInfoRequest*,
                                                        v1::GetServerInfoResponse* response) {
  const grpc::Status auth = shared_.Authorize(*context);
  return RunUnary(context, "GetServerInfo", auth, 1, [this, response](RequestLog&) {
    response->set_generator_version(kGeneratorVersion);
    response->set_region_side_in_d(kRegionSideInD);
    response->set_precision_range_in_d(kPrecisionRangeInD);
    response->set_field_region_side_in_r_max(kFieldRegionSideInRMax);
    response->set_max_layers(kMaxLayers);
    v1::Limits& limits = *response->mutable_limits();
    limits.set_max_page_size(shared_.config.max_page_size);
    limits.set_max_query_area(shared_.config.max_query_area);
    limits.set_max_stream_area(shared_.config.max_stream_area);
    limits.set_max_verify_area(shared_.config.max_verify_area);
    limits.set_max_in_flight(shared_.config.max_in_flight);
    limits.set_max_nearest_batch(shared_.config.max_nearest_batch);
    limits.set_max_noise_grid_samples(shared_.config.max_noise_grid_samples);
    limits.set_max_follow_area(shared_.config.max_follow_area);
    limits.set_max_nearest_regions(shared_.config.max_nearest_regions);
    limits.set_max_streams_in_flight(shared_.config.max_streams_in_flight);
    limits.set_stream_stall_seconds(shared_.config.stream_stall_seconds);
    limits.set_follow_stall_seconds(shared_.config.follow_stall_seconds);
    limits.set_follow_idle_seconds(shared_.config.follow_idle_seconds);
    limits.set_max_in_flight_cost(shared_.config.max_in_flight_cost);
    limits.set_max_client_share(shared_.config.max_client_share);
    limits.set_rate_limit_per_second(shared_.config.rate_limit_per_second);
    limits.set_rate_limit_burst(shared_.config.rate_limit_burst);
    response->set_default_world(shared_.worlds.default_name());
    for (const auto& [name, world] : shared_.worlds.worlds()) {
      response->add_world_names(name);
      response->add_world_descriptions(world.Describe());
    }
    for (const auto& [name, raster] : shared_.worlds.rasters().rasters()) {
      *response->add_rasters() = RasterInfoMessage(raster);
    }
    return grpc::Status::OK;
  });
}

}  // namespace scallop::server
