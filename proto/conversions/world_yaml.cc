// WorldMessageFromYaml: each key read into the message it mirrors; WorldFromYaml: that message
// read as a request's would be (its rasters from a catalog), then World::Create.
#include "world_yaml.h"

#include <optional>

#include "world_messages.h"

namespace scallop {
namespace {

// A `radius_field` as the message it mirrors (the proto's field names), its raster by the name it
// gives; keys named `where`.noise.KEY and so on.
StatusOr<v1::RadiusField> RadiusFieldFromYaml(const YAML::Node& node, const std::string& where) {
  if (Status keys = CheckYamlKeys(node, {"noise", "raster"}, where); !keys.ok()) return keys;
  v1::RadiusField message;
  if (const YAML::Node noise = node["noise"]) {
    const std::string at = where + ".noise";
    if (Status keys = CheckYamlKeys(
            noise, {"r_min", "r_max", "frequency", "octaves", "gain", "noise_seed"}, at);
        !keys.ok()) {
      return keys;
    }
    v1::NoiseRadiusField& out = *message.mutable_noise();
    out.set_r_min(noise["r_min"].as<double>(0.0));
    out.set_r_max(noise["r_max"].as<double>(0.0));
    out.set_frequency(noise["frequency"].as<double>(0.0));
    out.set_octaves(noise["octaves"].as<int32_t>(0));
    out.set_gain(noise["gain"].as<double>(0.0));
    out.set_noise_seed(noise["noise_seed"].as<uint64_t>(0));
  }
  if (const YAML::Node raster = node["raster"]) {
    const std::string at = where + ".raster";
    if (node["noise"]) return InvalidArgument(where + ": give noise or raster, not both");
    if (Status keys = CheckYamlKeys(
            raster, {"raster_name", "origin_x", "origin_y", "pixel_size", "r_min", "r_max"}, at);
        !keys.ok()) {
      return keys;
    }
    v1::RasterRadiusField& out = *message.mutable_raster();
    out.set_raster_name(raster["raster_name"].as<std::string>(""));
    out.set_origin_x(raster["origin_x"].as<double>(0.0));
    out.set_origin_y(raster["origin_y"].as<double>(0.0));
    out.set_pixel_size(raster["pixel_size"].as<double>(0.0));
    out.set_r_min(raster["r_min"].as<double>(0.0));
    out.set_r_max(raster["r_max"].as<double>(0.0));
  }
  return message;
}

// The `radius_field` of `holder` (a world or a layer) into `out`, if it has one.
Status ReadOptionalField(const YAML::Node& holder, const std::string& where, v1::RadiusField& out,
                         bool& has) {
  has = false;
  if (!holder["radius_field"]) return Status::Ok();
  StatusOr<v1::RadiusField> read =
      RadiusFieldFromYaml(holder["radius_field"], where + ".radius_field");
  if (!read.ok()) return read.status();
  out = *std::move(read);
  has = true;
  return Status::Ok();
}

}  // namespace

Status CheckYamlKeys(const YAML::Node& node, const std::set<std::string>& known,
                     const std::string& where) {
  if (!node.IsMap()) return InvalidArgument(where + ": must be a map");
  for (const auto& entry : node) {
    const std::string key = entry.first.as<std::string>();
    if (!known.contains(key)) return InvalidArgument(where + ": unknown key '" + key + "'");
  }
  return Status::Ok();
}

StatusOr<v1::World> WorldMessageFromYaml(const YAML::Node& node, const std::string& where) {
  const std::set<std::string> known{"seed",         "min_distance", "algorithm", "density",
                                    "radius_field", "layers",       "exclusions"};
  if (Status keys = CheckYamlKeys(node, known, where); !keys.ok()) return keys;
  StatusOr<WorldAlgorithm> algorithm =
      ParseWorldAlgorithm(node["algorithm"].as<std::string>("a3"), where + ".algorithm");
  if (!algorithm.ok()) return algorithm.status();
  v1::World message = WorldToMessage(WorldSpec{.seed = node["seed"].as<uint64_t>(0),
                                               .min_distance = node["min_distance"].as<double>(1.0),
                                               .algorithm = *algorithm,
                                               .density = node["density"].as<double>(2.0)});
  bool has_field = false;
  if (Status field = ReadOptionalField(node, where, *message.mutable_radius_field(), has_field);
      !field.ok()) {
    return field;
  }
  if (!has_field) message.clear_radius_field();
  if (const YAML::Node layers = node["layers"]) {
    if (!layers.IsSequence()) return InvalidArgument(where + ".layers: must be a list");
    for (size_t k = 0; k < layers.size(); ++k) {
      const std::string at = where + ".layers[" + std::to_string(k) + "]";
      if (Status keys = CheckYamlKeys(layers[k], {"name", "min_distance", "radius_field"}, at);
          !keys.ok()) {
        return keys;
      }
      v1::Layer& layer = *message.add_layers();
      layer.set_name(layers[k]["name"].as<std::string>(""));
      layer.set_min_distance(layers[k]["min_distance"].as<double>(1.0));
      if (Status field = ReadOptionalField(layers[k], at, *layer.mutable_radius_field(), has_field);
          !field.ok()) {
        return field;
      }
      if (!has_field) layer.clear_radius_field();
    }
  }
  if (const YAML::Node exclusions = node["exclusions"]) {
    if (!exclusions.IsSequence()) return InvalidArgument(where + ".exclusions: must be a list");
    for (size_t n = 0; n < exclusions.size(); ++n) {
      const std::string at = where + ".exclusions[" + std::to_string(n) + "]";
      if (Status keys = CheckYamlKeys(exclusions[n], {"first", "second", "distance"}, at);
          !keys.ok()) {
        return keys;
      }
      v1::LayerExclusion& exclusion = *message.add_exclusions();
      exclusion.set_first(exclusions[n]["first"].as<std::string>(""));
      exclusion.set_second(exclusions[n]["second"].as<std::string>(""));
      exclusion.set_distance(exclusions[n]["distance"].as<double>(-1.0));
    }
  }
  return message;
}

StatusOr<World> WorldFromYaml(const YAML::Node& node, const RasterCatalog& rasters,
                              const std::string& where) {
  StatusOr<v1::World> message = WorldMessageFromYaml(node, where);
  if (!message.ok()) return message.status();
  StatusOr<WorldSpec> spec = WorldSpecFromMessage(*message, &rasters, where);
  if (!spec.ok()) return spec.status();
  StatusOr<World> world = World::Create(*spec);
  if (!world.ok()) return InvalidArgument(where + ": " + world.status().message());
  return world;
}

std::vector<std::string> RasterNamesInYaml(const YAML::Node& node) {
  std::vector<std::string> names;
  const auto add = [&](const YAML::Node& holder) {
    if (!holder.IsMap()) return;
    const YAML::Node field = holder["radius_field"];
    if (field && field.IsMap() && field["raster"] && field["raster"].IsMap() &&
        field["raster"]["raster_name"]) {
      names.push_back(field["raster"]["raster_name"].as<std::string>(""));
    }
  };
  add(node);
  if (node.IsMap() && node["layers"] && node["layers"].IsSequence()) {
    for (const YAML::Node& layer : node["layers"]) add(layer);
  }
  return names;
}

}  // namespace scallop
