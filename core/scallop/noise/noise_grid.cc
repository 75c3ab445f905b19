// Noise images: validation of the grid and evaluation through a
// NearestLookup, in batches of whole rows.
#include "scallop/noise/noise_grid.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "scallop/plane/region_layout.h"

namespace scallop {
namespace {

// Samples per NearestLookup call (whole rows, at least one): the default
// batch limit, so a call's buffers are those of an ordinary request (about
// 100 bytes a sample with the positions and results here).
constexpr int kSamplesPerCall = 1 << 16;

// Distinct region indices of origin + k * step, k in [0, count): the
// coordinates grow with k, so a new index is one that differs from the last.
int64_t DistinctRegionIndices(const RegionLayout& layout, double origin, int count, double step) {
  int64_t distinct = 0;
  int64_t last = 0;
  for (int k = 0; k < count; ++k) {
    const int64_t index = layout.IndexOf(NoiseSampleCoordinate(origin, k, step));
    if (k == 0 || index != last) ++distinct;
    last = index;
  }
  return distinct;
}

}  // namespace

const char* NoiseChannelName(NoiseChannel channel) {
  switch (channel) {
    case NoiseChannel::kF1:
      return "f1";
    case NoiseChannel::kF2:
      return "f2";
    case NoiseChannel::kF2MinusF1:
      return "f2-f1";
    case NoiseChannel::kId:
      return "id";
    case NoiseChannel::kCellValue:
      return "cell";
  }
  return "?";
}

StatusOr<NoiseChannel> ParseNoiseChannel(const std::string& name) {
  for (NoiseChannel channel : {NoiseChannel::kF1, NoiseChannel::kF2, NoiseChannel::kF2MinusF1,
                               NoiseChannel::kId, NoiseChannel::kCellValue}) {
    if (name == NoiseChannelName(channel)) return channel;
  }
  return InvalidArgument("channel: must be f1, f2, f2-f1, id or cell, got '" + name + "'");
}

Status ValidateNoiseGrid(const World& world, const NoiseGridSpec& spec, int64_t max_samples) {
  if (!std::isfinite(spec.origin.x)) return InvalidArgument("origin_x: must be finite");
  if (!std::isfinite(spec.origin.y)) return InvalidArgument("origin_y: must be finite");
  if (!(std::isfinite(spec.step) && spec.step > 0)) {
    return InvalidArgument("step: must be finite and > 0");
  }
  if (spec.width < 1) return InvalidArgument("width: must be >= 1");
  if (spec.height < 1) return InvalidArgument("height: must be >= 1");
  const int64_t samples = int64_t{spec.width} * spec.height;
  if (samples > max_samples) {
    return InvalidArgument("width * height: is " + std::to_string(samples) + ", must be at most " +
                           std::to_string(max_samples));
  }
  // Coordinates are monotone in the index (step > 0, and rounding preserves
  // order), so the first and last samples bound every other.
  const Vec2 corners[] = {{spec.origin.x, spec.origin.y},
                          {NoiseSampleCoordinate(spec.origin.x, spec.width - 1, spec.step),
                           NoiseSampleCoordinate(spec.origin.y, spec.height - 1, spec.step)}};
  for (size_t k = 0; k < 2; ++k) {
    Status status = NearestLookup::ValidatePosition(world, corners[k], k);
    if (!status.ok()) {
      return {status.code(), std::string(k == 0 ? "origin" : "last sample") + ": " +
                                 status.message().substr(status.message().find(": ") + 2)};
    }
  }
  return Status::Ok();
}

int64_t NoiseGridRegions(const World& world, const NoiseGridSpec& spec) {
  const RegionLayout layout(world);
  return DistinctRegionIndices(layout, spec.origin.x, spec.width, spec.step) *
         DistinctRegionIndices(layout, spec.origin.y, spec.height, spec.step);
}

StatusOr<NoiseImage> EvaluateNoiseGrid(NearestLookup& lookup, const World& world,
                                       const NoiseGridSpec& spec, int64_t max_samples,
                                       const StopRequested& stop) {
  if (Status status = ValidateNoiseGrid(world, spec, max_samples); !status.ok()) return status;
  NoiseImage image{.width = spec.width, .height = spec.height, .values = {}, .ids = {}};
  const size_t samples = static_cast<size_t>(spec.width) * spec.height;
  if (spec.channel == NoiseChannel::kId) {
    image.ids.resize(samples);
  } else {
    image.values.resize(samples);
  }
  // Whole rows per call, up to about a default batch: each call pays a
  // cache lookup per region it visits, which row-at-a-time calls paid once
  // per row (about 16 positions apiece in a 1 d-step image).
  const int rows_per_call = std::max(1, kSamplesPerCall / spec.width);
  std::vector<Vec2> positions;
  std::vector<NearestPoint> results;
  for (int first_row = 0; first_row < spec.height; first_row += rows_per_call) {
    const int rows = std::min(rows_per_call, spec.height - first_row);
    positions.clear();
    for (int r = first_row; r < first_row + rows; ++r) {
      const double y = NoiseSampleCoordinate(spec.origin.y, r, spec.step);
      for (int c = 0; c < spec.width; ++c) {
        positions.push_back({NoiseSampleCoordinate(spec.origin.x, c, spec.step), y});
      }
    }
    results.resize(positions.size());
    if (Status status = lookup.Nearest(world, positions, results, stop); !status.ok()) {
      return status;
    }
    const size_t start = static_cast<size_t>(first_row) * spec.width;
    for (size_t k = 0; k < results.size(); ++k) {
      const NearestPoint& n = results[k];
      switch (spec.channel) {
        case NoiseChannel::kF1:
          image.values[start + k] = n.f1;
          break;
        case NoiseChannel::kF2:
          image.values[start + k] = n.f2;
          break;
        case NoiseChannel::kF2MinusF1:
          image.values[start + k] = n.f2 - n.f1;
          break;
        case NoiseChannel::kId:
          image.ids[start + k] = n.id;
          break;
        case NoiseChannel::kCellValue:
          image.values[start + k] = n.cell_value;
          break;
      }
    }
  }
  return image;
}

}  // namespace scallop
