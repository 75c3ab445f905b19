// Conversions between the API's radius field (scallop.v1.RadiusField) and the core's
// RadiusFieldSpec, shared by scallopd, its config and the CLI, so that all of them read the
// message's zero defaults (octaves 0, gain 0) and name bad fields the same way.
#pragma once

#include <string_view>

#include "raster_catalog.h"
#include "scallop/base/status.h"
#include "scallop/field/radius_field.h"
#include "scallop/v1/scallop.pb.h"

namespace scallop {

// The message's field, its raster looked up by name in `rasters`, validated
// (ValidateRadiusFieldSpec). Errors are INVALID_ARGUMENT naming the message's field under
// `where` ("world.radius_field.noise.frequency", "world.radius_field.raster.raster_name"):
// no kind set, an unknown raster name (the name is not echoed: it is the client's text; the
// loaded names are listed), a pixel_hash other than 0 and the raster's, and every range
// ValidateRadiusFieldSpec checks (r_min, r_max and their ratio, frequency, octaves, gain,
// pixel_size, origin, and the slope bound, named frequency or pixel_size). Cost: O(1) for
// noise; O(pixels) for a raster (its slope bound reads every pixel).
StatusOr<RadiusFieldSpec> RadiusFieldFromMessage(const v1::RadiusField& message,
                                                 const RasterCatalog& rasters,
                                                 std::string_view where = "world.radius_field");

// The spec as a message, every field explicit: a raster by `raster`'s name and pixel hash
// (null: the name left empty and the hash 0, for a client that names a raster it does not
// hold). A constant spec gives an empty message: a world without a field carries none.
v1::RadiusField RadiusFieldToMessage(const RadiusFieldSpec& spec, const NamedRaster* raster);

// The raster's name, size, bit depth and pixel hash, as ServerInfo and DescribeWorld report it.
v1::RasterInfo RasterInfoMessage(const NamedRaster& raster);

// The raster a spec's image came from, in the catalog: null for other kinds, a null catalog
// or an image it does not hold.
const NamedRaster* RasterOf(const RadiusFieldSpec& spec, const RasterCatalog* rasters);

}  // namespace scallop
