// StreamRemainder: the rest of the last region's row, then the rows below;
// StreamResumeRequests: that in the last chunk's layer, then the layers after it.
#include "stream_resume.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "world_messages.h"

namespace scallop::client {

std::vector<Rect> StreamRemainderInRegions(const Rect& rect, RegionKey last, double region_side) {
  // Each edge by the one expression RegionLayout uses, k * side, so that the
  // rectangles meet the regions the server walks exactly.
  const Rect region{
      static_cast<double>(last.i) * region_side, static_cast<double>(last.j) * region_side,
      static_cast<double>(last.i + 1) * region_side, static_cast<double>(last.j + 1) * region_side};
  std::vector<Rect> remainder;
  // The same row, right of `last`: its regions own exactly [region.x1, ...),
  // and the row's part of `rect` is [max(y0, region.y0), min(y1, region.y1)).
  const Rect row_rest{std::max(rect.x0, region.x1), std::max(rect.y0, region.y0), rect.x1,
                      std::min(rect.y1, region.y1)};
  if (row_rest.x0 < row_rest.x1 && row_rest.y0 < row_rest.y1) remainder.push_back(row_rest);
  if (region.y1 < rect.y1) remainder.push_back({rect.x0, region.y1, rect.x1, rect.y1});
  return remainder;
}

std::vector<Rect> StreamRemainder(const Rect& rect, RegionKey last, double min_distance) {
  return StreamRemainderInRegions(rect, last, RegionLayout(min_distance).side());
}

namespace {

bool PositiveSide(double side) { return std::isfinite(side) && side > 0; }

// The request with `rect` narrowed to each of the remainder's rectangles.
void AppendRemainder(const v1::StreamPointsRequest& request, RegionKey last, double region_side,
                     std::vector<v1::StreamPointsRequest>& requests) {
  for (const Rect& rest :
       StreamRemainderInRegions(RectFromMessage(request.rect()), last, region_side)) {
    requests.push_back(request);
    *requests.back().mutable_rect() = RectToMessage(rest);
  }
}

}  // namespace

StatusOr<std::vector<v1::StreamPointsRequest>> StreamResumeRequests(
    const v1::StreamPointsRequest& request, const v1::DescribeWorldResponse& world,
    std::optional<StreamPosition> last) {
  std::vector<v1::StreamPointsRequest> requests;
  if (!last.has_value()) {
    requests.push_back(request);
    return requests;
  }
  const int layer_count = world.layers_size();
  if (layer_count == 0) {
    if (!request.layers().empty()) {
      return InvalidArgument("layers: the world has no layers; leave it empty");
    }
    if (last->layer != 0) {
      return InvalidArgument("last.layer: must be 0 for a world without layers, got " +
                             std::to_string(last->layer));
    }
    if (!PositiveSide(world.region_side())) {
      return InvalidArgument("region_side: must be finite and > 0 (DescribeWorld's answer)");
    }
    AppendRemainder(request, last->region, world.region_side(), requests);
    return requests;
  }
  // The layers the stream asked for, by number: its filter, or every layer.
  std::vector<bool> asked(static_cast<size_t>(layer_count), request.layers().empty());
  for (const std::string& name : request.layers()) {
    int k = 0;
    while (k < layer_count && world.layers(k).name() != name) ++k;
    if (k == layer_count) return InvalidArgument("layers: no layer named '" + name + "'");
    asked[static_cast<size_t>(k)] = true;
  }
  if (last->layer >= static_cast<uint32_t>(layer_count) || !asked[last->layer]) {
    return InvalidArgument("last.layer: " + std::to_string(last->layer) +
                           " is not a layer the request asks for");
  }
  const v1::LayerDescription& own = world.layers(static_cast<int>(last->layer));
  if (!PositiveSide(own.region_side())) {
    return InvalidArgument("layers[" + std::to_string(last->layer) +
                           "].region_side: must be finite and > 0 (DescribeWorld's answer)");
  }
  v1::StreamPointsRequest rest_of_layer = request;
  rest_of_layer.clear_layers();
  rest_of_layer.add_layers(own.name());
  AppendRemainder(rest_of_layer, last->region, own.region_side(), requests);
  v1::StreamPointsRequest later_layers = request;
  later_layers.clear_layers();
  for (int k = static_cast<int>(last->layer) + 1; k < layer_count; ++k) {
    if (asked[static_cast<size_t>(k)]) later_layers.add_layers(world.layers(k).name());
  }
  if (!later_layers.layers().empty()) requests.push_back(std::move(later_layers));
  return requests;
}

}  // namespace scallop::client
