// Registration of the remote options and the call options they give.
#include "client/options/remote_options.h"

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
  for (const char* inline_option : {"--seed", "--min-distance", "--algorithm", "--density",
                                    "--radius-noise", "--radius-raster"}) {
    if (CLI::Option* option = command.get_option_no_throw(inline_option)) world->excludes(option);
  }
  command.add_option("--timeout", arguments.timeout_seconds, "Deadline of each call, seconds")
      ->check(CLI::NonNegativeNumber);
  if (server_optional) command.get_option("--timeout")->needs(server);
  AddConnectionOptions(command, arguments.connection);
}

StatusOr<v1::World> RemoteWorld(const WorldArguments& world) {
  // The World message has no layers yet (issue 19's API part): refuse rather than send a
  // world without them.
  if (!world.world_file.empty()) {
    return InvalidArgument("--world-file: local only for now (no --server)");
  }
  if (HasLayers(world.layers)) {
    return InvalidArgument("--layer: layered worlds are local only for now (no --server)");
  }
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
