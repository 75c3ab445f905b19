// Rasters by name: loading, hashing and lookup.
#include "raster_catalog.h"

#include <utility>

#include "scallop/field/raster_png.h"
#include "scallop/random/rng.h"

namespace scallop {

uint64_t RasterPixelHash(const RasterImage& image) {
  uint64_t h = HashWords({static_cast<uint64_t>(image.width), static_cast<uint64_t>(image.height),
                          static_cast<uint64_t>(image.bit_depth)});
  for (uint16_t v : image.pixels) h = Mix64(h + v + 0x9e3779b97f4a7c15ULL);
  return h;
}

Status RasterCatalog::Add(const std::string& name, RasterImage image, std::string_view where) {
  if (name.empty()) return InvalidArgument(std::string(where) + ": a raster needs a name");
  if (rasters_.contains(name)) {
    return InvalidArgument(std::string(where) + ": raster '" + name + "' is named twice");
  }
  const uint64_t hash = RasterPixelHash(image);
  rasters_[name] = {name, std::make_shared<const RasterImage>(std::move(image)), hash};
  return Status::Ok();
}

Status RasterCatalog::Load(const std::string& name, const std::string& path,
                           std::string_view where) {
  StatusOr<RasterImage> image = LoadGrayscalePng(path);
  if (!image.ok()) return InvalidArgument(std::string(where) + ": " + image.status().message());
  return Add(name, std::move(*image), where);
}

const NamedRaster* RasterCatalog::Find(std::string_view name) const {
  const auto found = rasters_.find(name);
  return found == rasters_.end() ? nullptr : &found->second;
}

const NamedRaster* RasterCatalog::FindImage(const RasterImage* image) const {
  for (const auto& [name, raster] : rasters_) {
    if (raster.image.get() == image) return &raster;
  }
  return nullptr;
}

std::string RasterCatalog::Names() const {
  std::string names;
  for (const auto& [name, raster] : rasters_) names += (names.empty() ? "" : ", ") + name;
  return names.empty() ? "none" : names;
}

}  // namespace scallop
