// Noise images: one channel of the cellular-noise basis (F1, F2, F2 - F1,
// nearest id, cell value) sampled on a regular grid, for terrain and texture
// tools. What the NoiseGrid RPC and `scallop noise` evaluate.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scallop/base/status.h"
#include "scallop/noise/nearest_lookup.h"

namespace scallop {

enum class NoiseChannel { kF1, kF2, kF2MinusF1, kId, kCellValue };

// "f1", "f2", "f2-f1", "id", "cell" (the CLI's names), and back.
const char* NoiseChannelName(NoiseChannel channel);
StatusOr<NoiseChannel> ParseNoiseChannel(const std::string& name);

// Sample (c, r), for column c in [0, width) and row r in [0, height), is at
// (origin.x + c * step, origin.y + r * step), computed in doubles exactly so:
// callers that tile a grid must compute positions the same way.
struct NoiseGridSpec {
  Vec2 origin;
  double step = 1;
  int width = 0;
  int height = 0;
  NoiseChannel channel = NoiseChannel::kF1;
};

// X coordinate of column c (and likewise y of row r): the one expression.
inline double NoiseSampleCoordinate(double origin, int index, double step) {
  return origin + static_cast<double>(index) * step;
}

// Row-major, row 0 first (lowest y): sample (c, r) is at r * width + c.
// `values` for every channel but kId, `ids` for kId.
struct NoiseImage {
  int width = 0;
  int height = 0;
  std::vector<double> values;
  std::vector<uint64_t> ids;
};

// Rejects (INVALID_ARGUMENT, naming the field): non-finite origin or step,
// step <= 0, width or height < 1, width * height > max_samples; OUT_OF_RANGE
// when a sample lies beyond 2^32 d (checked on the extreme samples, since
// coordinates grow with the index). Also the world's own checks.
Status ValidateNoiseGrid(const World& world, const NoiseGridSpec& spec, int64_t max_samples);

// The channel at every sample. Cost: that of NearestLookup::Nearest on
// width * height positions, in batches of whole rows of up to 65,536 samples
// (memory: the image plus about 100 bytes a sample of one batch); bounded by
// the regions the samples lie in (NoiseGridRegions). `stop` as in Nearest.
StatusOr<NoiseImage> EvaluateNoiseGrid(NearestLookup& lookup, const World& world,
                                       const NoiseGridSpec& spec, int64_t max_samples,
                                       const StopRequested& stop = nullptr);

// How many distinct regions (region_layout.h) the grid's samples lie in: the
// distinct region columns of its x coordinates times the distinct region rows
// of its y coordinates. O(width + height). REQUIRES: ValidateNoiseGrid ok.
int64_t NoiseGridRegions(const World& world, const NoiseGridSpec& spec);

}  // namespace scallop
