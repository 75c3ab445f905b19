// The options that name a world and a rectangle of it (--seed, --min-distance,
// --algorithm, --density, the radius field's options, --threads, --rect),
// shared by every command that queries the plane, locally or through a server.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "client/options/cli_fwd.h"
#include "client/options/field_options.h"
#include "client/options/layer_options.h"
#include "scallop/base/status.h"
#include "scallop/geometry/rect.h"
#include "scallop/plane/plane_engine.h"
#include "scallop/plane/world.h"

namespace scallop::cli {

// The options as typed; ParseWorldQuery turns them into checked values.
struct WorldArguments {
  std::string seed = "1";  // text: CLI11 would wrap "-1" and saturate 2^64 silently
  double min_distance = 1.0;
  std::string algorithm = "a3";
  double density = 2.0;
  int threads = 2;
  std::string rect;
  FieldArguments field;   // instead of --min-distance
  LayerArguments layers;  // instead of both: a layered world
  // A YAML file holding the whole world, as a named world of scallopd's config
  // (proto/conversions/world_yaml.h); instead of all the world options above.
  std::string world_file;
};

// Adds the world options to `command`, storing into `arguments`, which must
// outlive parsing. With `with_rect`, --rect is added and required, so a
// missing one is a parse error.
void AddWorldOptions(CLI::App& command, WorldArguments& arguments, bool with_rect = true);

// Adds --world-file, excluding the world options `command` already has (AddWorldOptions adds
// it; `analyze`, which takes the world options its own way, adds it after them).
void AddWorldFileOption(CLI::App& command, WorldArguments& arguments);

// Makes `file` (a --world-file option) exclude the world options `command` already has: the
// file gives the whole world.
void ExcludeWorldOptions(CLI::Option& file, CLI::App& command);

struct WorldQuery {
  World world;
  Rect rect;
  PlaneEngineOptions engine;
  // The layers --layers asks for (all for a world without layers).
  LayerMask layers = kAllLayers;
};

// Parses the world (ParseWorld), --rect and --threads (ParseEngineOptions)
// (World::Create). The rectangle's range and area are left to the rectangle
// rule (CheckQueryRect), which every query runs first with the command's
// limit. Errors name the option or the world field.
StatusOr<WorldQuery> ParseWorldQuery(const WorldArguments& arguments);

// The world alone (--seed, --min-distance, --algorithm, --density, or a radius
// field, its raster read from its file, or layers and exclusions; or --world-file), checked: the
// one way the CLI turns typed options into a World. A field's errors name its option
// (ParseLocalField).
StatusOr<World> ParseWorld(const WorldArguments& arguments);

// --world-file as the world a request to scallopd carries, for a file with raster fields: each
// raster_name names a raster the server loaded (its config's `rasters`), as in a named world of
// its config, and the server judges the values. The keys are checked here (INVALID_ARGUMENT
// led by "--world-file PATH").
StatusOr<v1::World> RemoteWorldOfFile(const std::string& path);

// The raster names (PNG paths) a --world-file's fields give, its own and its layers'; empty
// when it has none or cannot be read (ParseWorld then says why).
std::vector<std::string> RasterPathsOfWorldFile(const std::string& path);

// --seed as typed: all of the text an integer in 0..2^64-1, else an error
// naming --seed and the text.
StatusOr<uint64_t> ParseSeed(const std::string& text);

// The engine --threads asks for, checked (1..256); every command that runs an
// engine locally takes its threads from here.
StatusOr<PlaneEngineOptions> ParseEngineOptions(const WorldArguments& arguments);

}  // namespace scallop::cli
