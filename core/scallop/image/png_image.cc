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
  // libpng's full API, for the filter and strategy the simplified one does
  // not expose. Its errors longjmp back here; only `bytes`, made before
  // setjmp, is touched after it.
  std::string bytes;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png != nullptr ? png_create_info_struct(png) : nullptr;
  if (info == nullptr) {
    png_destroy_write_struct(&png, nullptr);
    return Status(StatusCode::kInternal, "cannot encode PNG: out of memory");
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return Status(StatusCode::kInternal, "cannot encode PNG");
  }
  png_set_write_fn(
      png, &bytes,
      [](png_structp writer, png_bytep data, png_size_t size) {
        static_cast<std::string*>(png_get_io_ptr(writer))
            ->append(reinterpret_cast<const char*>(data), size);
      },
      nullptr);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width),
               static_cast<png_uint_32>(image.height), 8,
               image.channels == 1 ? PNG_COLOR_TYPE_GRAY : PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  // Rendered pictures are long runs of one value: no filter and zlib's
  // run-length strategy take a fifth of the time of libpng's defaults
  // (adaptive filters, Z_FILTERED) for a file a quarter larger.
  png_set_filter(png, 0, PNG_FILTER_NONE);
  png_set_compression_strategy(png, 3 /* Z_RLE */);
  png_write_info(png, info);
  const size_t row_bytes = static_cast<size_t>(image.width) * image.channels;
  for (int row = 0; row < image.height; ++row) {
    png_write_row(png, image.pixels.data() + row * row_bytes);
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return bytes;
}

uint8_t GreyLevel(double value, double low, double high) {
  if (!(high > low) || std::isnan(value)) return 0;
  const double t = std::clamp((value - low) / (high - low), 0.0, 1.0);
  return static_cast<uint8_t>(std::lround(t * 255.0));
}

}  // namespace scallop
