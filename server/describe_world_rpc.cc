// DescribeWorld: a world's parameters with defaults filled in, and its geometry.
#include <algorithm>

#include "field_messages.h"
#include "scallop/plane/region_layout.h"
#include "scallop/plane/world_layers.h"
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
    log.set_world(world, resolved.description);
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
    if (const WorldLayers* layers = world.layers()) {
      const std::vector<int>& order = layers->generation_order();
      for (int k = 0; k < layers->count(); ++k) {
        const World& own = layers->world(k);
        const RegionLayout own_layout(own);
        // A later layer's world has a constant field: its kind is the spec's.
        const std::optional<RadiusFieldSpec>& spacing =
            world.spec().layers[static_cast<size_t>(k)].radius_field;
        v1::LayerDescription& layer = *response->add_layers();
        layer.set_name(layers->name(k));
        layer.set_region_side(own_layout.side());
        layer.set_r_min(own.min_distance());
        layer.set_r_max(own.max_spacing());
        layer.set_field_kind(
            std::string(RadiusFieldKindName(spacing ? spacing->kind : RadiusFieldKind::kConstant)));
        layer.set_generation_position(
            static_cast<uint32_t>(std::find(order.begin(), order.end(), k) - order.begin()));
        layer.set_id_index_bits(static_cast<uint32_t>(own_layout.point_id_index_bits()));
        layer.set_fingerprint(own.fingerprint());
        for (int b = 0; b < layers->count(); ++b) layer.add_exclusions(layers->exclusion(k, b));
      }
    }
    return grpc::Status::OK;
  });
}

}  // namespace scallop::server
