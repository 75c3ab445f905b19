// PNG files through libpng's simplified API, and the grey-level mapping the
// renderers share (see png_image.h).
#include "client/image/png_image.h"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace scallop::cli {

Status WritePng(const std::string& path, const Image8& image) {
  if (image.width <= 0 || image.height <= 0 || (image.channels != 1 && image.channels != 3) ||
      image.pixels.size() != static_cast<size_t>(image.width) * image.height * image.channels) {
    return InvalidArgument(path + ": image shape does not match its pixels");
  }
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  png.format = image.channels == 1 ? PNG_FORMAT_GRAY : PNG_FORMAT_RGB;
  const png_int_32 row_stride = image.width * image.channels;
  if (!png_image_write_to_file(&png, path.c_str(), 0, image.pixels.data(), row_stride, nullptr)) {
    std::string message = path + ": cannot write PNG: " + png.message;
    png_image_free(&png);
    return InvalidArgument(message);
  }
  return Status::Ok();
}

uint8_t GreyLevel(double value, double low, double high) {
  if (!(high > low) || std::isnan(value)) return 0;
  const double t = std::clamp((value - low) / (high - low), 0.0, 1.0);
  return static_cast<uint8_t>(std::lround(t * 255.0));
}

}  // namespace scallop::cli
