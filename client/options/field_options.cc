// Field options: registration with CLI11, and conversion to a checked RadiusFieldSpec (local) or
// a RadiusField message (remote).
#include "client/options/field_options.h"

#include <CLI/CLI.hpp>
#include <memory>
#include <string_view>
#include <utility>
#include <vector>

#include "client/options/rect_option.h"
#include "client/options/world_options.h"
#include "field_messages.h"
#include "scallop/field/raster_png.h"

namespace scallop::cli {
namespace {

// The field's parameters as typed (no raster read) and the raster's file or name.
struct TypedField {
  RadiusFieldSpec spec;
  std::string raster;
};

StatusOr<std::optional<TypedField>> ParseTypedField(const FieldArguments& arguments) {
  if (!HasField(arguments)) return std::optional<TypedField>();
  TypedField typed;
  RadiusFieldSpec& spec = typed.spec;
  if (!arguments.noise.empty()) {
    StatusOr<std::vector<double>> values =
        ParseNumbers(arguments.noise, "--radius-noise", 3, 4, "R_MIN,R_MAX,FREQUENCY[,OCTAVES]");
    if (!values.ok()) return values.status();
    spec.kind = RadiusFieldKind::kNoise;
    spec.r_min = (*values)[0];
    spec.r_max = (*values)[1];
    spec.frequency = (*values)[2];
    if (values->size() == 4) {
      const double octaves = (*values)[3];
      if (octaves != static_cast<int>(octaves)) {
        return InvalidArgument("--radius-noise: OCTAVES must be a whole number, got " +
                               arguments.noise);
      }
      spec.octaves = static_cast<int>(octaves);
    }
    StatusOr<uint64_t> seed = ParseSeed(arguments.noise_seed);
    if (!seed.ok()) {
      return InvalidArgument("--radius-noise-seed: must be an integer in 0..2^64-1, got '" +
                             arguments.noise_seed + "'");
    }
    spec.noise_seed = *seed;
    return std::optional<TypedField>(std::move(typed));
  }
  spec.kind = RadiusFieldKind::kRaster;
  typed.raster = arguments.raster;
  StatusOr<std::vector<double>> range =
      ParseNumbers(arguments.radius_range, "--radius-range", 2, 2, "R_MIN,R_MAX");
  if (!range.ok()) return range.status();
  spec.r_min = (*range)[0];
  spec.r_max = (*range)[1];
  StatusOr<std::vector<double>> origin =
      ParseNumbers(arguments.raster_origin, "--raster-origin", 2, 2, "X,Y");
  if (!origin.ok()) return origin.status();
  spec.raster_origin = {(*origin)[0], (*origin)[1]};
  spec.pixel_size = arguments.raster_pixel;
  return std::optional<TypedField>(std::move(typed));
}

// The core names the spec's field first ("field.frequency too high ..."); a person typed an
// option, so the message leads with the option that sets that field.
Status NamedByOption(const Status& status, RadiusFieldKind kind) {
  const std::string& message = status.message();
  std::string_view option = "--radius-raster";  // the image itself
  if (kind == RadiusFieldKind::kNoise) {
    option = "--radius-noise";
  } else if (message.starts_with("field.")) {
    option = "--radius-range";
  } else if (message.starts_with("raster.pixel_size")) {
    option = "--raster-pixel";
  } else if (message.starts_with("raster.origin")) {
    option = "--raster-origin";
  }
  return {status.code(), std::string(option) + ": " + message};
}

}  // namespace

void AddFieldOptions(CLI::App& command, FieldArguments& arguments) {
  CLI::Option* noise =
      command
          .add_option("--radius-noise", arguments.noise,
                      "Radius field: value noise from R_MIN to R_MAX, FREQUENCY cycles per unit "
                      "(first octave), OCTAVES (1..8, default 3)")
          ->type_name("R_MIN,R_MAX,FREQUENCY[,OCTAVES]");
  command.add_option("--radius-noise-seed", arguments.noise_seed, "The noise's own seed")
      ->type_name("UINT")
      ->capture_default_str()
      ->needs(noise);
  CLI::Option* raster =
      command
          .add_option("--radius-raster", arguments.raster,
                      "Radius field from a grayscale PNG (8 or 16 bit; value 0 masks); with "
                      "--server, the name of a raster the server loaded")
          ->type_name("FILE|NAME");
  CLI::Option* range = command
                           .add_option("--radius-range", arguments.radius_range,
                                       "The radii the raster's values 1..max map onto")
                           ->type_name("R_MIN,R_MAX");
  CLI::Option* origin = command
                            .add_option("--raster-origin", arguments.raster_origin,
                                        "World position of the raster's lower-left corner")
                            ->type_name("X,Y")
                            ->capture_default_str();
  CLI::Option* pixel =
      command.add_option("--raster-pixel", arguments.raster_pixel, "A raster pixel's side")
          ->type_name("SIZE")
          ->capture_default_str();
  noise->excludes(raster);
  raster->needs(range);
  for (CLI::Option* placement : {range, origin, pixel}) placement->needs(raster);
  if (CLI::Option* d = command.get_option_no_throw("--min-distance")) {
    for (CLI::Option* field : {noise, raster}) field->excludes(d);
  }
}

Status CheckFieldAlgorithm(const FieldArguments& arguments, const std::string& algorithm) {
  if (!HasField(arguments) || algorithm == "a3") return Status::Ok();
  return InvalidArgument("--algorithm: a radius field is sampled by a3 only, got '" + algorithm +
                         "'");
}

bool HasField(const FieldArguments& arguments) {
  return !arguments.noise.empty() || !arguments.raster.empty();
}

StatusOr<std::optional<RadiusFieldSpec>> ParseLocalField(const FieldArguments& arguments) {
  StatusOr<std::optional<TypedField>> typed = ParseTypedField(arguments);
  if (!typed.ok()) return typed.status();
  if (!typed->has_value()) return std::optional<RadiusFieldSpec>();
  RadiusFieldSpec spec = (*typed)->spec;
  if (spec.kind == RadiusFieldKind::kRaster) {
    StatusOr<RasterImage> image = LoadGrayscalePng((*typed)->raster);
    if (!image.ok()) return InvalidArgument("--radius-raster: " + image.status().message());
    spec.raster = std::make_shared<const RasterImage>(std::move(*image));
  }
  if (Status status = ValidateRadiusFieldSpec(spec); !status.ok()) {
    return NamedByOption(status, spec.kind);
  }
  return std::optional<RadiusFieldSpec>(std::move(spec));
}

StatusOr<std::optional<v1::RadiusField>> ParseRemoteField(const FieldArguments& arguments) {
  StatusOr<std::optional<TypedField>> typed = ParseTypedField(arguments);
  if (!typed.ok()) return typed.status();
  if (!typed->has_value()) return std::optional<v1::RadiusField>();
  const TypedField& field = **typed;
  if (field.spec.kind == RadiusFieldKind::kNoise) {
    if (Status status = ValidateRadiusFieldSpec(field.spec); !status.ok()) {
      return NamedByOption(status, field.spec.kind);
    }
  }
  v1::RadiusField message = RadiusFieldToMessage(field.spec, nullptr);
  if (field.spec.kind == RadiusFieldKind::kRaster) {
    message.mutable_raster()->set_raster_name(field.raster);
  }
  return std::optional<v1::RadiusField>(std::move(message));
}

}  // namespace scallop::cli
