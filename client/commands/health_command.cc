// `scallop health`: the standard gRPC health check of a scallopd, as an exit
// code for probes (Docker HEALTHCHECK, Kubernetes exec probes, scripts):
// 0 when SERVING, 1 when NOT_SERVING or unreachable within the timeout, 2 when
// a --tls-* or token file cannot be read.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "client/commands/commands.h"
#include "client/options/connection_options.h"
#include "scallop_client.h"

namespace scallop::cli {
namespace {

struct HealthArguments {
  std::string server;
  double timeout_seconds = 2;
  bool quiet = false;
  std::string service;             // "": the whole server
  ConnectionArguments connection;  // TLS (the health service needs no token)
};

int RunHealth(const HealthArguments& arguments) {
  StatusOr<client::ScallopClient> connected = ConnectTo(arguments.server, arguments.connection);
  if (!connected.ok()) {
    std::cerr << "scallop health: " << connected.status().message() << '\n';
    return 2;
  }
  client::ScallopClient& client = *connected;
  bool serving = false;
  const grpc::Status status = client.CheckHealth(
      serving,
      {.timeout =
           std::chrono::milliseconds(static_cast<int64_t>(arguments.timeout_seconds * 1000))},
      arguments.service);
  if (!status.ok()) {
    if (!arguments.quiet) {
      std::cerr << "scallop health: " << client::DescribeStatus(status) << '\n';
    }
    return 1;
  }
  if (!arguments.quiet) std::cout << (serving ? "SERVING" : "NOT_SERVING") << '\n';
  return serving ? 0 : 1;
}

}  // namespace

CommandRunner RegisterHealth(CLI::App& app) {
  auto arguments = std::make_shared<HealthArguments>();
  CLI::App* command =
      app.add_subcommand("health", "Exit 0 if scallopd is SERVING, 1 if not or unreachable");
  command
      ->add_option("--server", arguments->server,
                   "scallopd address: HOST:PORT or a gRPC target (dns:///HOST:PORT, ...)")
      ->required();
  command->add_option("--timeout", arguments->timeout_seconds, "Seconds to wait for an answer")
      ->check(CLI::Range(0.001, 3600.0))
      ->default_str("2");
  command->add_flag("--quiet", arguments->quiet, "Print nothing; the exit code says it");
  command->add_option("--service", arguments->service,
                      "Health service to ask: none for the whole server (NOT_SERVING while "
                      "draining or saturated), 'liveness' for whether it answers at all");
  AddConnectionOptions(*command, arguments->connection);
  return [arguments] { return RunHealth(*arguments); };
}

}  // namespace scallop::cli
