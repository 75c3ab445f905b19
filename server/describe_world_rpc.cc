// DescribeWorld: a world's parameters with defaults filled in, and its geometry.
#include "field_messages.h"
#include "scallop/plane/region_layout.h"
#include "server/scallop_service.h"
#include "world_messages.h"

namespace scallop::server {

grpc::ServerUnaryReactor* ScallopService::DescribeWorld(grpc::CallbackServerContext* context,
                                                        const v1::DescribeWorldRequest* request,
                                                        v1::DescribeWorldResponse* response) {
  const grpc::Status auth = shared_.Authorize(*context, *request);
  return RunUnary(context, "DescribeWorld", auth, 1, [this, request, response](RequestLog& log) {
    ResolvedWorld resolved;
    if (grpc::Status status = shared_.worlds.Resolve(*request, resolved); !status.ok())
      return status;
    const World& world = resolved.world;
    log.set_world(world.Describe());
    const RegionLayout layout(world);
    *response->mutable_world() = shared_.worlds.ToMessage(world);
    response->set_name(resolved.name);
    response->set_description(world.Describe());
    response->set_region_side(layout.side());
    response->set_precision_limit(layout.precision_limit());
    response->set_fingerprint(world.fingerprint());
    const RadiusField* field = world.radius_field();
    response->set_r_min(field != nullptr ? field->r_min() : world.min_distance());
    response->set_r_max(world.max_spacing());
    response->set_field_kind(std::string(
        RadiusFieldKindName(field != nullptr ? field->kind() : RadiusFieldKind::kConstant)));
    if (const NamedRaster* raster =
            field != nullptr ? RasterOf(field->spec(), &shared_.worlds.rasters()) : nullptr) {
      *response->mutable_raster() = RasterInfoMessage(*raster);
    }
    return grpc::Status::OK;
  });
}

}  // namespace scallop::server
