// The options that give a world (or a bounded run) a radius field instead of one minimum
// distance: --radius-noise R_MIN,R_MAX,FREQUENCY[,OCTAVES] (and --radius-noise-seed), or
// --radius-raster FILE|NAME with --raster-origin, --raster-pixel and --radius-range. Shared by
// every command that takes a world, locally (the raster read from a file) or through scallopd
// (a raster the server loaded, by name).
#pragma once

#include <optional>
#include <string>

#include "client/options/cli_fwd.h"
#include "scallop/base/status.h"
#include "scallop/field/radius_field.h"
#include "scallop/v1/scallop.pb.h"

namespace scallop::cli {

// The options as typed.
struct FieldArguments {
  std::string noise;                  // R_MIN,R_MAX,FREQUENCY[,OCTAVES]
  std::string noise_seed = "0";       // the noise's own seed, 0..2^64-1
  std::string raster;                 // a grayscale PNG file; with --server, a raster's name
  std::string raster_origin = "0,0";  // X,Y of the image's lower-left corner
  double raster_pixel = 1.0;          // a pixel's side in world units
  std::string radius_range;           // R_MIN,R_MAX the raster's values map onto
};

// Adds the field options to `command`, storing into `arguments` (which must outlive parsing).
// Each field kind excludes the other and --min-distance (when the command has it); the raster's
// placement options need --radius-raster, and --radius-raster needs --radius-range.
void AddFieldOptions(CLI::App& command, FieldArguments& arguments);

// OK unless a field option was given with an --algorithm other than a3: a radius field is
// sampled by A3's growth only (INVALID_ARGUMENT naming --algorithm).
Status CheckFieldAlgorithm(const FieldArguments& arguments, const std::string& algorithm);

// True when a field option was given (the world is a field world).
bool HasField(const FieldArguments& arguments);

// The field for a local run: nullopt without field options; else the spec, its raster read from
// the file (LoadGrayscalePng: missing, not a PNG, not grayscale, too large) and validated
// (ValidateRadiusFieldSpec). Errors are INVALID_ARGUMENT naming the option that sets the bad
// value, then the core's message: "--radius-noise: field.frequency too high ...",
// "--raster-pixel: raster.pixel_size ...", "--radius-raster: raster ...".
StatusOr<std::optional<RadiusFieldSpec>> ParseLocalField(const FieldArguments& arguments);

// The field for a request to scallopd: nullopt without field options; else the message, a raster
// by name (the server judges the name and the raster's slope; a noise field is validated here,
// as ParseLocalField does, so a bad one exits before any call).
StatusOr<std::optional<v1::RadiusField>> ParseRemoteField(const FieldArguments& arguments);

}  // namespace scallop::cli
