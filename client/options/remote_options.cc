// Registration of the remote options and the call options they give.
#include "client/options/remote_options.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <map>
#include <string>

namespace scallop::cli {

void AddRemoteOptions(CLI::App& command, RemoteArguments& arguments, bool server_optional) {
  CLI::Option* server =
      command.add_option("--server", arguments.server,
                         "scallopd address: HOST:PORT or a gRPC target (dns:///HOST:PORT, "
                         "ipv4:A:PORT,B:PORT), calls balanced round_robin");
  if (!server_optional) server->required();
  CLI::Option* world =
      command.add_option("--world", arguments.world_name, "A world configured on the server");
  if (server_optional) world->needs(server);
  for (const char* inline_option :
       {"--seed", "--min-distance", "--algorithm", "--density", "--radius-noise", "--radius-raster",
        "--layer", "--exclusion", "--world-file"}) {
    if (CLI::Option* option = command.get_option_no_throw(inline_option)) world->excludes(option);
  }
  command.add_option("--timeout", arguments.timeout_seconds, "Deadline of each call, seconds")
      ->check(CLI::NonNegativeNumber);
  if (server_optional) command.get_option("--timeout")->needs(server);
  AddConnectionOptions(command, arguments.connection);
}

namespace {

// A layered world for a request: a raster layer names the server's raster (judged there, as
// --radius-raster is); without one, the whole world is checked here first, so bad values exit
// 2 without a call.
StatusOr<v1::World> RemoteLayeredWorld(const WorldArguments& world) {
  StatusOr<std::vector<v1::Layer>> layers = ParseRemoteLayers(world.layers);
  if (!layers.ok()) return layers.status();
  const bool named_raster = std::any_of(layers->begin(), layers->end(), [](const v1::Layer& l) {
    return l.radius_field().has_raster();
  });
  if (!named_raster) {
    StatusOr<World> parsed = ParseWorld(world);
    if (!parsed.ok()) return parsed.status();
    return WorldToMessage(parsed->spec());
  }
  StatusOr<uint64_t> seed = ParseSeed(world.seed);
  if (!seed.ok()) return seed.status();
  StatusOr<WorldAlgorithm> algorithm = ParseWorldAlgorithm(world.algorithm);
  if (!algorithm.ok()) return algorithm.status();
  StatusOr<std::vector<LayerExclusionSpec>> exclusions = ParseExclusions(world.layers);
  if (!exclusions.ok()) return exclusions.status();
  v1::World message = WorldToMessage(WorldSpec{.seed = *seed,
                                               .algorithm = *algorithm,
                                               .density = world.density,
                                               .exclusions = std::move(*exclusions)});
  for (v1::Layer& layer : *layers) *message.add_layers() = std::move(layer);
  return message;
}

}  // namespace

StatusOr<v1::World> RemoteWorld(const WorldArguments& world) {
  if (!world.world_file.empty()) {
    // A raster_name is then the server's raster, as in its config (the server judges it);
    // without one the whole world is checked here first, so bad values exit 2 without a call.
    if (!RasterPathsOfWorldFile(world.world_file).empty()) {
      return RemoteWorldOfFile(world.world_file);
    }
    StatusOr<World> parsed = ParseWorld(world);
    if (!parsed.ok()) return parsed.status();
    return WorldToMessage(parsed->spec());
  }
  if (HasLayers(world.layers)) return RemoteLayeredWorld(world);
  if (Status status = CheckFieldAlgorithm(world.field, world.algorithm); !status.ok()) {
    return status;
  }
  StatusOr<std::optional<v1::RadiusField>> field = ParseRemoteField(world.field);
  if (!field.ok()) return field.status();
  if (!field->has_value()) {
    StatusOr<World> parsed = ParseWorld(world);
    if (!parsed.ok()) return parsed.status();
    return WorldToMessage(*parsed);
  }
  // The rest of the world as for a constant one; the field's min_distance is its r_min.
  WorldArguments rest = world;
  rest.field = {};
  StatusOr<World> parsed = ParseWorld(rest);
  if (!parsed.ok()) return parsed.status();
  v1::World message = WorldToMessage(*parsed);
  *message.mutable_radius_field() = std::move(**field);
  return message;
}

void AddEncodingOption(CLI::App& command, v1::PointEncoding& encoding) {
  const std::map<std::string, v1::PointEncoding> encodings{
      {"packed", v1::POINT_ENCODING_PACKED},
      {"exact", v1::POINT_ENCODING_EXACT},
      {"quantised", v1::POINT_ENCODING_QUANTISED}};
  command
      .add_option("--encoding", encoding,
                  "How points travel: packed (24 bytes a point), exact (the same doubles, 8-15 "
                  "bytes) or quantised (2^-13 d, about 4.3 bytes); docs/wire.md")
      ->transform(CLI::CheckedTransformer(encodings, CLI::ignore_case))
      ->option_text("packed|exact|quantised (default packed)");
}

client::CallOptions CallOptionsFor(const RemoteArguments& arguments) {
  client::CallOptions options;
  if (arguments.timeout_seconds > 0) {
    options.timeout =
        std::chrono::milliseconds(static_cast<int64_t>(arguments.timeout_seconds * 1000.0 + 0.5));
  }
  return options;
}

}  // namespace scallop::cli
