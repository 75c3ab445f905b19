// The checks every rectangle passes before the engine sees it: present,
// finite, ordered, in the precision range (PlaneEngine::ValidateQuery), and
// within the method's cost limits.
#pragma once

#include <grpcpp/support/status.h>

#include "scallop/plane/plane_engine.h"

namespace scallop::server {

// `rect` of `world` checked against `max_area` d^2 (named `limit_name` in the
// message) and against the regions it crosses: at most max_area / 64 + 16.
// A square of the largest area crosses far fewer, so only thin rectangles
// meet that bound, which would otherwise cost a region each at almost no area.
// INVALID_ARGUMENT or OUT_OF_RANGE with the field named; OK otherwise.
grpc::Status CheckQueryRect(const PlaneEngine& engine, const World& world, bool has_rect,
                            const Rect& rect, double max_area, const char* limit_name);

// How many regions the half-open rectangle overlaps (as a double: it may be huge).
// REQUIRES: rect valid (finite, ordered).
double RegionsCrossed(const World& world, const Rect& rect);

}  // namespace scallop::server
