// Radius field conversions: message to spec (with the raster looked up and the errors named by
// the message's fields) and back.
#include "field_messages.h"

#include <array>
#include <string>
#include <utility>

namespace scallop {
namespace {

// The core names fields after the spec (field.r_min, raster.pixel_size); a message's reader
// wants the message's field. Pairs of (core name, field of the kind's message).
using FieldNames = std::array<std::pair<std::string_view, std::string_view>, 5>;
constexpr FieldNames kNoiseNames{{{"field.r_min", "noise.r_min"},
                                  {"field.r_max", "noise.r_max"},
                                  {"field.frequency", "noise.frequency"},
                                  {"field.octaves", "noise.octaves"},
                                  {"field.gain", "noise.gain"}}};
constexpr FieldNames kRasterNames{{{"field.r_min", "raster.r_min"},
                                   {"field.r_max", "raster.r_max"},
                                   {"raster.pixel_size", "raster.pixel_size"},
                                   {"raster.origin", "raster.origin_x/origin_y"},
                                   // the image itself (bit depth, size): the name chose it
                                   {"raster", "raster.raster_name"}}};

// Every core name in the message replaced by `where`.field, the leading one followed by a colon.
// A name counts only as a whole word, so "raster" does not match inside "raster.pixel_size",
// and a name without a dot only at the start.
Status Renamed(const Status& status, const FieldNames& names, std::string_view where) {
  const std::string& text = status.message();
  std::string out;
  size_t k = 0;
  while (k < text.size()) {
    bool replaced = false;
    const bool word_start = k == 0 || text[k - 1] == ' ' || text[k - 1] == '(';
    for (const auto& [core, field] : names) {
      if (!word_start || text.compare(k, core.size(), core) != 0) continue;
      // A bare word ("raster") is a field name only where it leads; in prose it is prose.
      if (k != 0 && core.find('.') == std::string_view::npos) continue;
      const size_t end = k + core.size();
      if (end < text.size() && text[end] != ' ' && text[end] != ',' && text[end] != ';' &&
          text[end] != ':' && text[end] != ')') {
        continue;  // "raster" inside "raster.pixels": the next name handles it, or none
      }
      out.append(where).append(1, '.').append(field);
      if (k == 0) out.append(1, ':');
      k = end;
      replaced = true;
      break;
    }
    if (!replaced) out.push_back(text[k++]);
  }
  return {status.code(), std::move(out)};
}

Status Bad(std::string_view where, std::string_view field, const std::string& what) {
  std::string message(where);
  message.append(1, '.').append(field).append(": ").append(what);
  return InvalidArgument(std::move(message));
}

}  // namespace

StatusOr<RadiusFieldSpec> RadiusFieldFromMessage(const v1::RadiusField& message,
                                                 const RasterCatalog& rasters,
                                                 std::string_view where) {
  RadiusFieldSpec spec;
  const FieldNames* names = nullptr;
  switch (message.kind_case()) {
    case v1::RadiusField::kNoise: {
      const v1::NoiseRadiusField& noise = message.noise();
      spec.kind = RadiusFieldKind::kNoise;
      spec.r_min = noise.r_min();
      spec.r_max = noise.r_max();
      spec.frequency = noise.frequency();
      // proto3 cannot tell an unset field from 0, and 0 is never a valid octave count or gain.
      spec.octaves = noise.octaves() == 0 ? RadiusFieldSpec{}.octaves : noise.octaves();
      spec.gain = noise.gain() == 0.0 ? RadiusFieldSpec{}.gain : noise.gain();
      spec.noise_seed = noise.noise_seed();
      names = &kNoiseNames;
      break;
    }
    case v1::RadiusField::kRaster: {
      const v1::RasterRadiusField& raster = message.raster();
      const NamedRaster* named = rasters.Find(raster.raster_name());
      if (named == nullptr) {
        return Bad(where, "raster.raster_name",
                   raster.raster_name().empty()
                       ? "required: the name of a raster the server loaded (loaded: " +
                             rasters.Names() + ")"
                       : "no raster of that name is loaded (loaded: " + rasters.Names() + ")");
      }
      if (raster.pixel_hash() != 0 && raster.pixel_hash() != named->pixel_hash) {
        return Bad(where, "raster.pixel_hash",
                   "the loaded raster's pixels hash otherwise (its pixel_hash is " +
                       std::to_string(named->pixel_hash) + "); 0 accepts any");
      }
      spec.kind = RadiusFieldKind::kRaster;
      spec.raster = named->image;
      spec.raster_origin = {raster.origin_x(), raster.origin_y()};
      spec.pixel_size = raster.pixel_size();
      spec.r_min = raster.r_min();
      spec.r_max = raster.r_max();
      names = &kRasterNames;
      break;
    }
    default:
      return InvalidArgument(std::string(where) +
                             ": set noise or raster (leave radius_field unset for the constant "
                             "spacing min_distance)");
  }
  if (Status status = ValidateRadiusFieldSpec(spec); !status.ok()) {
    return Renamed(status, *names, where);
  }
  return spec;
}

v1::RadiusField RadiusFieldToMessage(const RadiusFieldSpec& spec, const NamedRaster* raster) {
  v1::RadiusField message;
  switch (spec.kind) {
    case RadiusFieldKind::kConstant:
      break;
    case RadiusFieldKind::kNoise: {
      v1::NoiseRadiusField& noise = *message.mutable_noise();
      noise.set_r_min(spec.r_min);
      noise.set_r_max(spec.r_max);
      noise.set_frequency(spec.frequency);
      noise.set_octaves(spec.octaves);
      noise.set_gain(spec.gain);
      noise.set_noise_seed(spec.noise_seed);
      break;
    }
    case RadiusFieldKind::kRaster: {
      v1::RasterRadiusField& out = *message.mutable_raster();
      if (raster != nullptr) {
        out.set_raster_name(raster->name);
        out.set_pixel_hash(raster->pixel_hash);
      }
      out.set_origin_x(spec.raster_origin.x);
      out.set_origin_y(spec.raster_origin.y);
      out.set_pixel_size(spec.pixel_size);
      out.set_r_min(spec.r_min);
      out.set_r_max(spec.r_max);
      break;
    }
  }
  return message;
}

v1::RasterInfo RasterInfoMessage(const NamedRaster& raster) {
  v1::RasterInfo message;
  message.set_name(raster.name);
  message.set_width(raster.image->width);
  message.set_height(raster.image->height);
  message.set_bit_depth(raster.image->bit_depth);
  message.set_pixel_hash(raster.pixel_hash);
  return message;
}

const NamedRaster* RasterOf(const RadiusFieldSpec& spec, const RasterCatalog* rasters) {
  if (spec.kind != RadiusFieldKind::kRaster || rasters == nullptr) return nullptr;
  return rasters->FindImage(spec.raster.get());
}

}  // namespace scallop
