// Region warm-up by blocks of regions, with a stop check between blocks.
#include "server/region_warmup.h"

#include <algorithm>

#include "scallop/plane/layer_regions.h"
#include "scallop/plane/query_rect.h"
#include "server/status_mapping.h"

namespace scallop::server {
namespace {

// Block side in regions: 64 regions are tens of milliseconds of cold
// generation, the longest a stop waits, and keep the engine's threads busy.
constexpr int64_t kBlockSide = 8;

}  // namespace

grpc::Status WarmRegions(PlaneEngine& engine, const World& world, const Rect& rect,
                         const std::function<bool()>& stop, LayerMask layers) {
  if (world.layers() != nullptr) {
    for (const int layer : LayersAskedFor(world, layers)) {
      if (grpc::Status status = WarmRegions(engine, WorldOfLayer(world, layer), rect, stop);
          !status.ok()) {
        return status;
      }
    }
    return grpc::Status::OK;
  }
  const RegionLayout layout(world);
  const auto [low, high] = RegionsOverlapping(layout, rect);
  for (int64_t j = low.j; j <= high.j; j += kBlockSide) {
    for (int64_t i = low.i; i <= high.i; i += kBlockSide) {
      if (stop && stop()) {
        return {grpc::StatusCode::CANCELLED,
                "server: stopped, the client cancelled or its deadline passed"};
      }
      const Rect first = layout.RegionRect({i, j});
      const Rect last = layout.RegionRect(
          {std::min(high.i, i + kBlockSide - 1), std::min(high.j, j + kBlockSide - 1)});
      const Rect block{std::max(rect.x0, first.x0), std::max(rect.y0, first.y0),
                       std::min(rect.x1, last.x1), std::min(rect.y1, last.y1)};
      StatusOr<std::vector<RegionHandle>> regions = engine.Regions(world, block);
      if (!regions.ok()) return ToGrpcStatus(regions.status());
    }
  }
  return grpc::Status::OK;
}

}  // namespace scallop::server
