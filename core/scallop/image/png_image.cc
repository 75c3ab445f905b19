// PNG files through libpng's simplified API, and the grey-level mapping the
// renderers share (see png_image.h).
#include "scallop/image/png_image.h"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace scallop {

namespace {

bool ShapeMatchesPixels(const Image8& image) {
  return image.width > 0 && image.height > 0 && (image.channels == 1 || image.channels == 3) &&
         image.pixels.size() == static_cast<size_t>(image.width) * image.height * image.channels;
}

// libpng's description of `image`; REQUIRES: ShapeMatchesPixels(image).
png_image Describe(const Image8& image) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  png.format = image.channels == 1 ? PNG_FORMAT_GRAY : PNG_FORMAT_RGB;
  return png;
}

}  // namespace

Status WritePng(const std::string& path, const Image8& image) {
  if (!ShapeMatchesPixels(image)) {
    return InvalidArgument(path + ": image shape does not match its pixels");
  }
  png_image png = Describe(image);
  const png_int_32 row_stride = image.width * image.channels;
  if (!png_image_write_to_file(&png, path.c_str(), 0, image.pixels.data(), row_stride, nullptr)) {
    std::string message = path + ": cannot write PNG: " + png.message;
    png_image_free(&png);
    return InvalidArgument(message);
  }
  return Status::Ok();
}

StatusOr<std::string> EncodePng(const Image8& image) {
  if (!ShapeMatchesPixels(image)) return InvalidArgument("image shape does not match its pixels");
  png_image png = Describe(image);
  const png_int_32 row_stride = image.width * image.channels;
  // First call sizes the file, second writes it.
  png_alloc_size_t size = 0;
  if (png_image_write_to_memory(&png, nullptr, &size, 0, image.pixels.data(), row_stride,
                                nullptr)) {
    std::string bytes(size, '\0');
    if (png_image_write_to_memory(&png, bytes.data(), &size, 0, image.pixels.data(), row_stride,
                                  nullptr)) {
      bytes.resize(size);
      return bytes;
    }
  }
  std::string message = std::string("cannot encode PNG: ") + png.message;
  png_image_free(&png);
  return InvalidArgument(message);
}

uint8_t GreyLevel(double value, double low, double high) {
  if (!(high > low) || std::isnan(value)) return 0;
  const double t = std::clamp((value - low) / (high - low), 0.0, 1.0);
  return static_cast<uint8_t>(std::lround(t * 255.0));
}

}  // namespace scallop
