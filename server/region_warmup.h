// Generating a query's regions in small steps, so that a call whose client
// has gone (cancelled, or past its deadline) stops between steps instead of
// generating a whole cold rectangle, seconds of work, for nobody.
#pragma once

#include <grpcpp/support/status.h>

#include <functional>

#include "scallop/plane/plane_engine.h"

namespace scallop::server {

// Generates (into the engine's cache) every region a query of `rect` reads,
// a block of up to 8 x 8 regions at a time, calling `stop` before each block:
// CANCELLED as soon as it returns true. The points are those the query would
// give (blocks only change the order of generation).
// Errors as PlaneEngine::Regions. REQUIRES: ValidateQuery(world, rect) ok.
// A layered world: the regions of each layer in `layers`, one layer after
// another (QueryRegions' parts; earlier layers come with the later ones).
grpc::Status WarmRegions(PlaneEngine& engine, const World& world, const Rect& rect,
                         const std::function<bool()>& stop, LayerMask layers = kAllLayers);

}  // namespace scallop::server
