// Encodes 8-bit images as PNG through libpng's simplified API, to files (the
// CLI's pictures: noise fields, periodograms, plots) or to memory (scallopd's
// PNG tiles).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scallop/base/status.h"

namespace scallop {

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

// The PNG file's bytes: rows unfiltered, zlib's run-length strategy (fast on
// rendered pictures, about 2 ms for 256 x 256). INVALID_ARGUMENT when the
// image's shape is inconsistent, INTERNAL if libpng fails. The same image
// gives the same bytes with the same libpng and zlib (scallopd's ETags rely
// on it).
StatusOr<std::string> EncodePng(const Image8& image);

// Maps value in [low, high] to a grey byte, 0 at low, 255 at high, clamping
// outside; NaN maps to 0. For rendering scalar fields.
uint8_t GreyLevel(double value, double low, double high);

}  // namespace scallop
