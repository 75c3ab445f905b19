// World options: registration with CLI11, and conversion to a checked World,
// seed and engine.
#include "client/options/world_options.h"

#include <CLI/CLI.hpp>
#include <charconv>
#include <filesystem>

#include "client/options/rect_option.h"
#include "raster_catalog.h"
#include "world_yaml.h"

namespace scallop::cli {

// A bound so that a typo cannot start a million threads; beyond the machine's
// cores more threads only add start-up cost.
constexpr int kMaxThreads = 256;

void AddWorldOptions(CLI::App& command, WorldArguments& arguments, bool with_rect) {
  command.add_option("--seed", arguments.seed, "World seed, 0..2^64-1")
      ->type_name("UINT")
      ->capture_default_str();
  command.add_option("--min-distance", arguments.min_distance, "Minimum distance d between points")
      ->capture_default_str();
  command.add_option("--algorithm", arguments.algorithm, "a1, a2 or a3")->capture_default_str();
  command.add_option("--density", arguments.density, "r'/2r in (1, 2], a1 and a2 only")
      ->capture_default_str();
  AddFieldOptions(command, arguments.field);
  AddLayerOptions(command, arguments.layers);
  AddWorldFileOption(command, arguments);
  command.add_option("--threads", arguments.threads, "Threads generating regions")
      ->capture_default_str();
  if (with_rect) {
    command.add_option("--rect", arguments.rect, "Rectangle X0,Y0,X1,Y1 (half-open)")->required();
  }
}

void AddWorldFileOption(CLI::App& command, WorldArguments& arguments) {
  CLI::Option* file = command.add_option(
      "--world-file", arguments.world_file,
      "The world as YAML: the keys of a named world in scallopd's config (seed, min_distance, "
      "algorithm, density, radius_field, layers, exclusions); a raster_name is a PNG path "
      "relative to the file, or with --server the name of a raster the server loaded");
  ExcludeWorldOptions(*file, command);
}

void ExcludeWorldOptions(CLI::Option& file, CLI::App& command) {
  for (const char* option : {"--seed", "--min-distance", "--algorithm", "--density",
                             "--radius-noise", "--radius-raster", "--layer", "--exclusion"}) {
    if (CLI::Option* other = command.get_option_no_throw(option)) file.excludes(other);
  }
}

StatusOr<WorldQuery> ParseWorldQuery(const WorldArguments& arguments) {
  WorldQuery query;
  StatusOr<World> world = ParseWorld(arguments);
  if (!world.ok()) return world.status();
  query.world = *world;
  StatusOr<Rect> rect = ParseRect(arguments.rect, "--rect");
  if (!rect.ok()) return rect.status();
  query.rect = *rect;
  StatusOr<PlaneEngineOptions> engine = ParseEngineOptions(arguments);
  if (!engine.ok()) return engine.status();
  query.engine = *engine;
  StatusOr<LayerMask> layers = ParseLayerFilter(arguments.layers, query.world);
  if (!layers.ok()) return layers.status();
  query.layers = *layers;
  return query;
}

namespace {

// --world-file: the YAML world, each raster_name read as a PNG path relative to the file.
StatusOr<World> WorldFromFile(const std::string& path) {
  const std::string where = "--world-file " + path;
  try {
    const YAML::Node node = YAML::LoadFile(path);
    RasterCatalog rasters;
    for (const std::string& name : RasterNamesInYaml(node)) {
      if (name.empty() || rasters.Find(name) != nullptr) continue;
      std::filesystem::path file = name;
      if (file.is_relative()) file = std::filesystem::path(path).parent_path() / file;
      if (Status loaded = rasters.Load(name, file.string(), where); !loaded.ok()) return loaded;
    }
    return WorldFromYaml(node, rasters, where);
  } catch (const YAML::Exception& e) {
    return InvalidArgument(where + ": " + e.what());
  }
}

}  // namespace

StatusOr<v1::World> RemoteWorldOfFile(const std::string& path) {
  const std::string where = "--world-file " + path;
  try {
    return WorldMessageFromYaml(YAML::LoadFile(path), where);
  } catch (const YAML::Exception& e) {
    return InvalidArgument(where + ": " + e.what());
  }
}

std::vector<std::string> RasterPathsOfWorldFile(const std::string& path) {
  try {
    return RasterNamesInYaml(YAML::LoadFile(path));
  } catch (const YAML::Exception&) {
    return {};
  }
}

StatusOr<World> ParseWorld(const WorldArguments& arguments) {
  if (!arguments.world_file.empty()) return WorldFromFile(arguments.world_file);
  StatusOr<uint64_t> seed = ParseSeed(arguments.seed);
  if (!seed.ok()) return seed.status();
  StatusOr<WorldAlgorithm> algorithm = ParseWorldAlgorithm(arguments.algorithm);
  if (!algorithm.ok()) return algorithm.status();
  if (Status status = CheckFieldAlgorithm(arguments.field, arguments.algorithm); !status.ok()) {
    return status;
  }
  StatusOr<std::optional<RadiusFieldSpec>> field = ParseLocalField(arguments.field);
  if (!field.ok()) return field.status();
  StatusOr<std::vector<LayerSpec>> layers = ParseLayers(arguments.layers);
  if (!layers.ok()) return layers.status();
  StatusOr<std::vector<LayerExclusionSpec>> exclusions = ParseExclusions(arguments.layers);
  if (!exclusions.ok()) return exclusions.status();
  return World::Create({.seed = *seed,
                        .min_distance = arguments.min_distance,
                        .algorithm = *algorithm,
                        .density = arguments.density,
                        .radius_field = std::move(*field),
                        .layers = std::move(*layers),
                        .exclusions = std::move(*exclusions)});
}

StatusOr<uint64_t> ParseSeed(const std::string& text) {
  uint64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size()) {
    return InvalidArgument("--seed: must be an integer in 0..2^64-1, got '" + text + "'");
  }
  return value;
}

StatusOr<PlaneEngineOptions> ParseEngineOptions(const WorldArguments& arguments) {
  if (arguments.threads < 1 || arguments.threads > kMaxThreads) {
    return InvalidArgument("--threads: must be in 1.." + std::to_string(kMaxThreads) + ", got " +
                           std::to_string(arguments.threads));
  }
  PlaneEngineOptions engine;
  engine.threads = arguments.threads;
  return engine;
}

}  // namespace scallop::cli
