// Output of points fetched from scallopd, in the formats of `scallop plane`:
// whole sets (SVG needs the world's d and region side, which a named world's
// caller learns from DescribeWorld), and CSV written chunk by chunk as a
// stream or a Follow call delivers it.
#pragma once

#include <ostream>
#include <span>
#include <vector>

#include "client/output/point_output.h"
#include "scallop/plane/plane_engine.h"
#include "scallop_client.h"

namespace scallop::cli {

// Writes `points` of `rect` (with `radii`, R at each point, for a field
// world: empty otherwise); for SVG first asks the server for the world's d
// and region side. Returns the status of that call (OK for the other formats).
template <typename Request>
grpc::Status WriteRemotePoints(client::ScallopClient& client, const Request& request,
                               const client::CallOptions& options, PointFormat format, bool seams,
                               const PlanePoints& points, std::span<const double> radii,
                               std::ostream& out) {
  SvgStyle style;
  if (format == PointFormat::kSvg) {
    v1::DescribeWorldRequest describe;
    if (request.has_world()) *describe.mutable_world() = request.world();
    if (!request.world_name().empty()) describe.set_world_name(request.world_name());
    v1::DescribeWorldResponse world;
    if (grpc::Status status = client.DescribeWorld(describe, world, options); !status.ok()) {
      return status;
    }
    style = {.seam_spacing = seams ? world.region_side() : 0.0,
             .dot_radius = world.world().min_distance() / 2};
  }
  const Rect rect{request.rect().x0(), request.rect().y0(), request.rect().x1(),
                  request.rect().y1()};
  WritePoints(out, format, points.positions, points.ids, radii, rect, style);
  return grpc::Status::OK;
}

// CSV of points that arrive in parts, written as they come so memory stays
// bounded: the same text as WritePoints' CSV. The header goes out with the
// first part that has points (with r when it carries radii), or at Finish
// when none had, then with r when `field_world` says so.
class IncrementalCsv {
 public:
  IncrementalCsv(std::ostream& out, bool field_world) : out_(out), field_world_(field_world) {}
  // Writes the rows of `points` (packed or encoded); returns how many.
  // INVALID_ARGUMENT, nothing written, for a malformed message (ReadPoints).
  StatusOr<int> Write(const v1::Points& points);
  void Finish();

 private:
  std::ostream& out_;
  bool field_world_;
  bool header_written_ = false;
};

}  // namespace scallop::cli
