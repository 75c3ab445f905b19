// The raster radius field's PNG loader (core/scallop/field/raster_png.h) on
// arbitrary files. Invariants: no crash, no abort from libpng, no allocation
// past the size limits; a refusal names raster or raster.path; an accepted
// image is within kMaxRasterSide and kMaxRasterPixels, 8 or 16 bit, with
// width * height pixels, each within its bit depth.
#include <cstdint>
#include <string>

#include "fuzz/fuzz_check.h"
#include "fuzz/fuzz_input_file.h"
#include "scallop/field/raster_png.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace scallop;
  const std::string& path = fuzz::WriteInputFile(data, size, ".png");
  const StatusOr<RasterImage> image = LoadGrayscalePng(path);
  if (!image.ok()) {
    SCALLOP_FUZZ_CHECK(image.status().message().starts_with("raster"),
                       "error naming neither raster nor raster.path: " + image.status().message());
    return 0;
  }
  SCALLOP_FUZZ_CHECK(image->width >= 1 && image->height >= 1 && image->width <= kMaxRasterSide &&
                         image->height <= kMaxRasterSide &&
                         int64_t{image->width} * image->height <= kMaxRasterPixels,
                     "accepted an image past the size limits");
  SCALLOP_FUZZ_CHECK(image->bit_depth == 8 || image->bit_depth == 16, "bad bit depth");
  SCALLOP_FUZZ_CHECK(image->pixels.size() == static_cast<size_t>(image->width) * image->height,
                     "pixel count differs from width * height");
  const uint32_t max_value = (1u << image->bit_depth) - 1;
  for (uint16_t v : image->pixels) SCALLOP_FUZZ_CHECK(v <= max_value, "pixel past its bit depth");
  return 0;
}
