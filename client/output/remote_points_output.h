// Output of points fetched from scallopd, in the formats of `scallop plane`;
// SVG needs the world's d (dot size, seams), which a named world's caller
// learns from DescribeWorld.
#pragma once

#include <ostream>

#include "client/output/point_output.h"
#include "scallop/plane/plane_engine.h"
#include "scallop_client.h"

namespace scallop::cli {

// Writes `points` of `rect`; for SVG first asks the server for the world's d.
// Returns the status of that call (OK for the other formats).
template <typename Request>
grpc::Status WriteRemotePoints(client::ScallopClient& client, const Request& request,
                               const client::CallOptions& options, PointFormat format, bool seams,
                               const PlanePoints& points, std::ostream& out) {
  double d = 1.0;
  if (format == PointFormat::kSvg) {
    v1::DescribeWorldRequest describe;
    if (request.has_world()) *describe.mutable_world() = request.world();
    if (!request.world_name().empty()) describe.set_world_name(request.world_name());
    v1::DescribeWorldResponse world;
    if (grpc::Status status = client.DescribeWorld(describe, world, options); !status.ok()) {
      return status;
    }
    d = world.world().min_distance();
  }
  const SvgStyle style{.seam_spacing = seams ? 16 * d : 0.0, .dot_radius = d / 2};
  const Rect rect{request.rect().x0(), request.rect().y0(), request.rect().x1(),
                  request.rect().y1()};
  WritePoints(out, format, points.positions, points.ids, {}, rect, style);
  return grpc::Status::OK;
}

}  // namespace scallop::cli
