// Loads a grayscale PNG (8 or 16 bit) into a RasterImage for a raster radius field, with the
// size limits of radius_field.h checked before any pixel memory is allocated.
#pragma once

#include <string>

#include "scallop/base/status.h"
#include "scallop/field/radius_field.h"

namespace scallop {

// Reads `path`. Rows come back bottom-up (the file's last row is row 0, the lowest y).
// Rejects, with INVALID_ARGUMENT naming "raster.path": a missing or unreadable file, a file that
// is not a PNG or is corrupt; "raster": a colour, palette or alpha image, a bit depth other than
// 8 or 16, a side above kMaxRasterSide or more than kMaxRasterPixels pixels (checked from the
// header, before decoding). Never throws or aborts on bad files. Cost: O(pixels).
StatusOr<RasterImage> LoadGrayscalePng(const std::string& path);

}  // namespace scallop
