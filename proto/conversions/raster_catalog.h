// RasterCatalog: grayscale rasters by name, what a raster radius field in a message names
// (RasterRadiusField.raster_name). scallopd fills one from its config at start; the CLI fills
// one from --radius-raster FILE. Immutable once filled, so request threads share it unlocked.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <string_view>

#include "scallop/base/status.h"
#include "scallop/field/radius_field.h"

namespace scallop {

// A 64-bit hash of an image's width, height, bit depth and pixels (rows bottom-up, each pixel a
// word): h = HashWords({width, height, bit_depth}), then h = Mix64(h + pixel + golden) per pixel.
// Replicas whose files decode alike get the same hash. O(pixels).
uint64_t RasterPixelHash(const RasterImage& image);

struct NamedRaster {
  std::string name;
  std::shared_ptr<const RasterImage> image;
  uint64_t pixel_hash = 0;  // RasterPixelHash(*image)
};

class RasterCatalog {
 public:
  // Adds `image` under `name`: INVALID_ARGUMENT naming `where` for an empty name or one already
  // taken. O(pixels) (the hash).
  Status Add(const std::string& name, RasterImage image, std::string_view where = "rasters");

  // Loads the grayscale PNG at `path` (LoadGrayscalePng: missing, not a PNG, not grayscale, too
  // large) and adds it under `name`; errors are prefixed with `where` (a config key, an option).
  Status Load(const std::string& name, const std::string& path, std::string_view where);

  // Null when no raster has that name. O(log n).
  const NamedRaster* Find(std::string_view name) const;
  // The entry holding exactly this image (by address), null if none: how a world's raster,
  // which holds only the pixels, finds its name again for an answer. O(n).
  const NamedRaster* FindImage(const RasterImage* image) const;

  // Sorted by name.
  const std::map<std::string, NamedRaster, std::less<>>& rasters() const { return rasters_; }
  // "a, b, c", or "none", for messages naming what is loaded.
  std::string Names() const;

 private:
  std::map<std::string, NamedRaster, std::less<>> rasters_;
};

}  // namespace scallop
