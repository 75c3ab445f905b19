// Resuming a StreamPoints call that broke (its replica went away, a proxy
// cut it): the stream's chunks come one region at a time in region row, then
// column order (a layered world's layer by layer, in the world's order), so
// what is still missing after the last chunk received is the rest of that
// region's row and the rows after it, at most two rectangles, then the
// layers after it. Streaming them in order continues the stream exactly: no
// point missing, none twice (docs/streaming.md, "When a stream breaks").
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "scallop/base/status.h"
#include "scallop/geometry/rect.h"
#include "scallop/plane/region_layout.h"
#include "scallop/v1/scallop.pb.h"

namespace scallop::client {

// The rectangles whose streams, read one after the other, give the chunks of
// a stream of `rect` that come after the chunk of region `last`, in regions
// of side `region_side` (DescribeWorldResponse.region_side, or a layer's
// LayerDescription.region_side). Empty when `last` was the rectangle's last
// region. O(1).
// REQUIRES: region_side finite and > 0; `last` a region `rect` overlaps.
std::vector<Rect> StreamRemainderInRegions(const Rect& rect, RegionKey last, double region_side);

// The same for a constant world of spacing `min_distance` (regions of 16 d).
// A radius-field world's regions are 6 r_max: use StreamRemainderInRegions
// with its region_side.
std::vector<Rect> StreamRemainder(const Rect& rect, RegionKey last, double min_distance);

// Where a stream stopped: the layer and region of the last chunk received.
struct StreamPosition {
  uint32_t layer = 0;  // PointsChunk.layer: 0 for a world without layers
  RegionKey region;    // PointsChunk.region_i, region_j
  static StreamPosition Of(const v1::PointsChunk& chunk) {
    return {chunk.layer(), {chunk.region_i(), chunk.region_j()}};
  }
};

// The requests whose streams, read one after the other, give the chunks of
// `request`'s stream that come after `last`, for any world. `world` is
// DescribeWorld's answer for the request's world (its region side; for a
// layered world each layer's name and region side). Each request is
// `request` (world, encoding) with:
// - a world without layers: `rect` narrowed to each of
//   StreamRemainderInRegions' rectangles;
// - a layered world: the same in the regions of last.layer, with `layers`
//   that layer alone; then, when the stream asked for layers after it (its
//   `layers`, or every layer when empty), one request of the whole `rect`
//   with `layers` those, in the world's order.
// Without `last` (the stream broke before its first chunk): `request` itself.
// Empty when nothing can follow `last`. Some requests may stream no chunk
// (their regions hold no point of `rect`). O(layers + request.layers).
// INVALID_ARGUMENT naming the field when `world` has no positive region side
// (`region_side`, `layers[k].region_side`), `request.layers` names a layer
// `world` has not or is given for a world without layers (`layers`), or
// `last.layer` is not a layer the request asked for (`last.layer`).
StatusOr<std::vector<v1::StreamPointsRequest>> StreamResumeRequests(
    const v1::StreamPointsRequest& request, const v1::DescribeWorldResponse& world,
    std::optional<StreamPosition> last);

}  // namespace scallop::client
