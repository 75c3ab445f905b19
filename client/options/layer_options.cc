// Layer options: registration with CLI11, and conversion to layer and exclusion specs and a
// layer filter.
#include "client/options/layer_options.h"

#include <CLI/CLI.hpp>
#include <sstream>

#include "client/options/field_options.h"
#include "client/options/rect_option.h"
#include "field_messages.h"
#include "scallop/plane/world_layers.h"

namespace scallop::cli {
namespace {

std::vector<std::string> Split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, separator)) parts.push_back(part);
  if (!text.empty() && text.back() == separator) parts.emplace_back();
  return parts;
}

// A layer's radius field in the field options' own syntax, so that its values are read and
// checked exactly as --radius-noise's and --radius-raster's are.
StatusOr<FieldArguments> FieldOfLayer(const std::string& name, const std::string& spacing) {
  FieldArguments field;
  const std::string where = "--layer " + name;
  if (spacing.starts_with("noise:")) {
    std::vector<std::string> values = Split(spacing.substr(6), ',');
    if (values.size() == 5) {
      field.noise_seed = values.back();
      values.pop_back();
    }
    std::string joined;
    for (const std::string& v : values) joined += (joined.empty() ? "" : ",") + v;
    field.noise = joined;
    return field;
  }
  const std::vector<std::string> parts = Split(spacing.substr(7), ':');
  if (parts.size() < 2 || parts.size() > 4 || parts[0].empty()) {
    return InvalidArgument(where + ": expected raster:FILE:R_MIN,R_MAX[:X,Y[:PIXEL]], got '" +
                           spacing + "'");
  }
  field.raster = parts[0];
  field.radius_range = parts[1];
  if (parts.size() >= 3) field.raster_origin = parts[2];
  if (parts.size() == 4) {
    StatusOr<std::vector<double>> pixel = ParseNumbers(parts[3], where, 1, 1, "PIXEL");
    if (!pixel.ok()) return pixel.status();
    field.raster_pixel = (*pixel)[0];
  }
  return field;
}

}  // namespace

void AddLayerOptions(CLI::App& command, LayerArguments& arguments) {
  CLI::Option* layer =
      command
          .add_option("--layer", arguments.layers,
                      "A layer (repeat for more, at most 16): its name and its spacing, a "
                      "distance or a radius field, noise:R_MIN,R_MAX,FREQUENCY[,OCTAVES[,SEED]] "
                      "or raster:FILE:R_MIN,R_MAX[:X,Y[:PIXEL]]")
          ->type_name("NAME=SPACING")
          ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  command
      .add_option("--exclusion", arguments.exclusions,
                  "Least distance between two layers' points (repeat; pairs not given: "
                  "(sum of 1/r^2 over the layers generated up to the later one)^-1/2)")
      ->type_name("NAME,NAME=DISTANCE")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->needs(layer);
  // Not tied to --layer: a layered world may come from --world-file or a server's --world.
  command
      .add_option("--layers", arguments.filter,
                  "Only these layers' points (nearest, noise: the one layer to answer for)")
      ->type_name("NAME[,NAME]");
  for (const char* single : {"--min-distance", "--radius-noise", "--radius-raster"}) {
    if (CLI::Option* option = command.get_option_no_throw(single)) layer->excludes(option);
  }
}

bool HasLayers(const LayerArguments& arguments) { return !arguments.layers.empty(); }

StatusOr<std::vector<LayerSpec>> ParseLayers(const LayerArguments& arguments) {
  std::vector<LayerSpec> layers;
  for (const std::string& text : arguments.layers) {
    const size_t equals = text.find('=');
    if (equals == std::string::npos || equals == 0 || equals + 1 == text.size()) {
      return InvalidArgument("--layer: expected NAME=SPACING, got '" + text + "'");
    }
    LayerSpec layer{.name = text.substr(0, equals)};
    const std::string spacing = text.substr(equals + 1);
    if (spacing.starts_with("noise:") || spacing.starts_with("raster:")) {
      StatusOr<FieldArguments> field = FieldOfLayer(layer.name, spacing);
      if (!field.ok()) return field.status();
      StatusOr<std::optional<RadiusFieldSpec>> parsed = ParseLocalField(*field);
      if (!parsed.ok()) {
        // "--radius-noise: field.frequency ..." becomes "--layer NAME: field.frequency ...".
        std::string message = parsed.status().message();
        message = message.substr(message.find(": ") + 2);
        return InvalidArgument("--layer " + layer.name + ": " + message);
      }
      layer.radius_field = **parsed;
    } else {
      StatusOr<std::vector<double>> d = ParseNumbers(spacing, "--layer " + layer.name, 1, 1,
                                                     "a distance, noise:... or raster:...");
      if (!d.ok()) return d.status();
      layer.min_distance = (*d)[0];
    }
    layers.push_back(std::move(layer));
  }
  return layers;
}

StatusOr<std::vector<LayerExclusionSpec>> ParseExclusions(const LayerArguments& arguments) {
  std::vector<LayerExclusionSpec> exclusions;
  for (const std::string& text : arguments.exclusions) {
    const size_t equals = text.find('=');
    const size_t comma = text.find(',');
    if (equals == std::string::npos || comma == std::string::npos || comma > equals) {
      return InvalidArgument("--exclusion: expected NAME,NAME=DISTANCE, got '" + text + "'");
    }
    StatusOr<std::vector<double>> d =
        ParseNumbers(text.substr(equals + 1), "--exclusion", 1, 1, "NAME,NAME=DISTANCE");
    if (!d.ok()) return d.status();
    exclusions.push_back({.first = text.substr(0, comma),
                          .second = text.substr(comma + 1, equals - comma - 1),
                          .distance = (*d)[0]});
  }
  return exclusions;
}

StatusOr<std::vector<v1::Layer>> ParseRemoteLayers(const LayerArguments& arguments) {
  std::vector<v1::Layer> layers;
  for (const std::string& text : arguments.layers) {
    const size_t equals = text.find('=');
    const std::string spacing = equals == std::string::npos ? "" : text.substr(equals + 1);
    if (!spacing.starts_with("raster:")) {
      StatusOr<std::vector<LayerSpec>> local =
          ParseLayers({.layers = {text}, .exclusions = {}, .filter = {}});
      if (!local.ok()) return local.status();
      *layers.emplace_back().mutable_name() = (*local)[0].name;
      layers.back().set_min_distance((*local)[0].min_distance);
      if ((*local)[0].radius_field.has_value()) {
        *layers.back().mutable_radius_field() =
            RadiusFieldToMessage(*(*local)[0].radius_field, nullptr);
      }
      continue;
    }
    const std::string name = text.substr(0, equals);
    StatusOr<FieldArguments> field = FieldOfLayer(name, spacing);
    if (!field.ok()) return field.status();
    StatusOr<std::optional<v1::RadiusField>> remote = ParseRemoteField(*field);
    if (!remote.ok()) {
      std::string message = remote.status().message();
      message = message.substr(message.find(": ") + 2);
      return InvalidArgument("--layer " + name + ": " + message);
    }
    v1::Layer& layer = layers.emplace_back();
    layer.set_name(name);
    *layer.mutable_radius_field() = **remote;
  }
  return layers;
}

std::vector<std::string> LayerFilterNames(const LayerArguments& arguments) {
  if (arguments.filter.empty()) return {};
  return Split(arguments.filter, ',');
}

StatusOr<std::string> SingleLayerName(const LayerArguments& arguments) {
  const std::vector<std::string> names = LayerFilterNames(arguments);
  if (names.size() > 1) {
    return InvalidArgument("--layers: the noise basis is one layer's; name one, got '" +
                           arguments.filter + "'");
  }
  return names.empty() ? std::string() : names[0];
}

StatusOr<World> NoiseBasisWorld(const LayerArguments& arguments, const World& world) {
  StatusOr<std::string> name = SingleLayerName(arguments);
  if (!name.ok()) return name.status();
  const WorldLayers* layers = world.layers();
  if (layers == nullptr) {
    if (name->empty()) return world;
    return InvalidArgument("--layers: the world has no layers");
  }
  std::string names;
  for (int k = 0; k < layers->count(); ++k) names += (k == 0 ? "" : ",") + layers->name(k);
  if (name->empty()) {
    return InvalidArgument("--layers: a layered world's noise basis is one layer's; name one of " +
                           names);
  }
  const int layer = layers->LayerNamed(*name);
  if (layer < 0) return InvalidArgument("--layers: no layer named '" + *name + "' (" + names + ")");
  return layers->world(layer);
}

StatusOr<LayerMask> ParseLayerFilter(const LayerArguments& arguments, const World& world) {
  if (arguments.filter.empty()) return kAllLayers;
  if (world.layers() == nullptr) {
    return InvalidArgument("--layers: the world has no layers");
  }
  LayerMask mask = 0;
  for (const std::string& name : Split(arguments.filter, ',')) {
    const int layer = world.layers()->LayerNamed(name);
    if (layer < 0) return InvalidArgument("--layers: no layer named '" + name + "'");
    mask |= LayerMask{1} << layer;
  }
  return mask;
}

}  // namespace scallop::cli
