// Writes 8-bit images as PNG files through libpng's simplified API, for the
// commands that render pictures (noise fields, periodograms, plots).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scallop/base/status.h"

namespace scallop::cli {

// An image of width x height pixels, row 0 at the top, `channels` bytes a
// pixel: 1 for grey, 3 for RGB.
struct Image8 {
  int width = 0;
  int height = 0;
  int channels = 1;
  std::vector<uint8_t> pixels;  // width * height * channels, row-major
};

// Writes `image` to `path`. INVALID_ARGUMENT naming the path when the image's
// shape is inconsistent or the file cannot be written.
Status WritePng(const std::string& path, const Image8& image);

// Maps value in [low, high] to a grey byte, 0 at low, 255 at high, clamping
// outside; NaN maps to 0. For rendering scalar fields.
uint8_t GreyLevel(double value, double low, double high);

}  // namespace scallop::cli
