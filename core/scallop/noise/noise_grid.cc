// Noise images: validation of the grid and row-by-row evaluation through a
// NearestLookup (one batch per row keeps memory to the image plus a row).
#include "scallop/noise/noise_grid.h"

#include <cmath>

namespace scallop {

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
  if (Status status = ValidateWorld(world); !status.ok()) return status;
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

StatusOr<NoiseImage> EvaluateNoiseGrid(NearestLookup& lookup, const World& world,
                                       const NoiseGridSpec& spec, int64_t max_samples) {
  if (Status status = ValidateNoiseGrid(world, spec, max_samples); !status.ok()) return status;
  NoiseImage image{.width = spec.width, .height = spec.height, .values = {}, .ids = {}};
  const size_t samples = static_cast<size_t>(spec.width) * spec.height;
  if (spec.channel == NoiseChannel::kId) {
    image.ids.resize(samples);
  } else {
    image.values.resize(samples);
  }
  std::vector<Vec2> row_positions(spec.width);
  std::vector<NearestPoint> row_results(spec.width);
  for (int r = 0; r < spec.height; ++r) {
    const double y = NoiseSampleCoordinate(spec.origin.y, r, spec.step);
    for (int c = 0; c < spec.width; ++c) {
      row_positions[c] = {NoiseSampleCoordinate(spec.origin.x, c, spec.step), y};
    }
    if (Status status = lookup.Nearest(world, row_positions, row_results); !status.ok()) {
      return status;
    }
    const size_t row_start = static_cast<size_t>(r) * spec.width;
    for (int c = 0; c < spec.width; ++c) {
      const NearestPoint& n = row_results[c];
      switch (spec.channel) {
        case NoiseChannel::kF1:
          image.values[row_start + c] = n.f1;
          break;
        case NoiseChannel::kF2:
          image.values[row_start + c] = n.f2;
          break;
        case NoiseChannel::kF2MinusF1:
          image.values[row_start + c] = n.f2 - n.f1;
          break;
        case NoiseChannel::kId:
          image.ids[row_start + c] = n.id;
          break;
        case NoiseChannel::kCellValue:
          image.values[row_start + c] = n.cell_value;
          break;
      }
    }
  }
  return image;
}

}  // namespace scallop
