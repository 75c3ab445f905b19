// Registration of the remote options and the call options they give.
#include "client/options/remote_options.h"

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
  for (const char* inline_option : {"--seed", "--min-distance", "--algorithm", "--density"}) {
    if (CLI::Option* option = command.get_option_no_throw(inline_option)) world->excludes(option);
  }
  command.add_option("--timeout", arguments.timeout_seconds, "Deadline of each call, seconds")
      ->check(CLI::NonNegativeNumber);
  if (server_optional) command.get_option("--timeout")->needs(server);
  AddConnectionOptions(command, arguments.connection);
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
