// Output of points fetched from scallopd, in the formats of `scallop plane`:
// whole sets (SVG needs the world's d and region side, which a named world's
// caller learns from DescribeWorld), and CSV written chunk by chunk as a
// stream or a Follow call delivers it.
#pragma once

#include <functional>
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "client/output/point_output.h"
#include "scallop/plane/plane_engine.h"
#include "scallop_client.h"

namespace scallop::cli {

// The layers' names of a layered world a request names: from the request's
// inline world, else from DescribeWorld (one call). Empty for other worlds.
template <typename Request>
grpc::Status RemoteLayerNames(client::ScallopClient& client, const Request& request,
                              const client::CallOptions& options, std::vector<std::string>& names,
                              v1::DescribeWorldResponse* described = nullptr) {
  names.clear();
  const v1::World* world = request.has_world() ? &request.world() : nullptr;
  v1::DescribeWorldResponse own;
  v1::DescribeWorldResponse& response = described != nullptr ? *described : own;
  if (world == nullptr) {
    v1::DescribeWorldRequest describe;
    if (!request.world_name().empty()) describe.set_world_name(request.world_name());
    if (grpc::Status status = client.DescribeWorld(describe, response, options); !status.ok()) {
      return status;
    }
    world = &response.world();
  }
  for (const v1::Layer& layer : world->layers()) names.push_back(layer.name());
  return grpc::Status::OK;
}

// Writes `points` of `rect` (with `radii`, R at each point, for a field
// world: empty otherwise; a layered world's with their layers, by name); for
// SVG first asks the server for the world's d and region side (and a
// layered world's layers' spacings, the disks of constant layers). Returns
// the status of the calls it makes.
template <typename Request>
grpc::Status WriteRemotePoints(client::ScallopClient& client, const Request& request,
                               const client::CallOptions& options, PointFormat format, bool seams,
                               const PlanePoints& points, std::span<const double> radii,
                               std::ostream& out) {
  SvgStyle style;
  v1::DescribeWorldResponse world;
  if (format == PointFormat::kSvg) {
    v1::DescribeWorldRequest describe;
    if (request.has_world()) *describe.mutable_world() = request.world();
    if (!request.world_name().empty()) describe.set_world_name(request.world_name());
    if (grpc::Status status = client.DescribeWorld(describe, world, options); !status.ok()) {
      return status;
    }
    style = {.seam_spacing = seams ? world.region_side() : 0.0,
             .dot_radius = world.world().min_distance() / 2};
  }
  std::vector<std::string> names;
  std::vector<double> disks(radii.begin(), radii.end());
  if (!points.layers.empty()) {
    if (format == PointFormat::kSvg) {
      for (const v1::Layer& layer : world.world().layers()) names.push_back(layer.name());
      // Constant layers send no radii: each disk at half its layer's d, as `scallop plane`.
      if (disks.empty()) {
        for (const uint8_t layer : points.layers) disks.push_back(world.layers(layer).r_min());
      }
    } else if (grpc::Status status = RemoteLayerNames(client, request, options, names);
               !status.ok()) {
      return status;
    }
  }
  const Rect rect{request.rect().x0(), request.rect().y0(), request.rect().x1(),
                  request.rect().y1()};
  WritePoints(out, format, points.positions, points.ids, disks, rect, style,
              {points.layers, names});
  return grpc::Status::OK;
}

// CSV of points that arrive in parts, written as they come so memory stays
// bounded: the same text as WritePoints' CSV. The header goes out with the
// first part that has points (with r when it carries radii, layer when it
// carries layers), or at Finish when none had, then with r when
// `field_world` says so. A layered world's layer names come from
// `layer_names`, called once, at the first part with layers.
class IncrementalCsv {
 public:
  using LayerNames = std::function<StatusOr<std::vector<std::string>>()>;
  IncrementalCsv(std::ostream& out, bool field_world, LayerNames layer_names = nullptr)
      : out_(out), field_world_(field_world), layer_names_(std::move(layer_names)) {}
  // Writes the rows of `points` (packed or encoded); returns how many.
  // INVALID_ARGUMENT, nothing written, for a malformed message (ReadPoints),
  // or points with layers when no names can be had.
  StatusOr<int> Write(const v1::Points& points);
  void Finish();

 private:
  std::ostream& out_;
  bool field_world_;
  LayerNames layer_names_;
  std::vector<std::string> names_;
  bool header_written_ = false;
};

// IncrementalCsv's names of the layered world `request` names (RemoteLayerNames).
template <typename Request>
IncrementalCsv::LayerNames LayerNamesFrom(client::ScallopClient& client, const Request& request,
                                          const client::CallOptions& options) {
  return [&client, request, options]() -> StatusOr<std::vector<std::string>> {
    std::vector<std::string> names;
    if (grpc::Status status = RemoteLayerNames(client, request, options, names); !status.ok()) {
      return InvalidArgument(client::DescribeStatus(status));
    }
    return names;
  };
}

}  // namespace scallop::cli
