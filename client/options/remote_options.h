// The options every command that talks to scallopd shares (--server, --world,
// --timeout), and the request fields they and the world options fill in.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "client/options/connection_options.h"
#include "client/options/world_options.h"
#include "scallop/v1/scallop.pb.h"
#include "scallop_client.h"
#include "world_messages.h"

namespace scallop::cli {

struct RemoteArguments {
  std::string server;              // HOST:PORT, required
  std::string world_name;          // a world configured on the server, instead of --seed...
  double timeout_seconds = 0;      // deadline of each call; 0 for none
  ConnectionArguments connection;  // TLS and token
};

// Adds --server (required unless `server_optional`, for commands that also run
// locally), --world (excludes the inline world options), --timeout and the
// connection options (TLS, token) to a
// command that already has the world options.
void AddRemoteOptions(CLI::App& command, RemoteArguments& arguments, bool server_optional = false);

client::CallOptions CallOptionsFor(const RemoteArguments& arguments);

// Sets the request's world: by name with --world, else inline from --seed,
// --min-distance, --algorithm and --density (checked here, so bad values exit 2
// without a call).
template <typename Request>
Status SetRequestWorld(const RemoteArguments& remote, const WorldArguments& world,
                       Request& request) {
  if (!remote.world_name.empty()) {
    request.set_world_name(remote.world_name);
    return Status::Ok();
  }
  StatusOr<World> parsed = ParseWorld(world);
  if (!parsed.ok()) return parsed.status();
  *request.mutable_world() = WorldToMessage(*parsed);
  return Status::Ok();
}

// The request's world and --rect, checked as for `scallop plane`.
template <typename Request>
Status SetRequestWorldAndRect(const RemoteArguments& remote, const WorldArguments& world,
                              Request& request) {
  if (Status status = SetRequestWorld(remote, world, request); !status.ok()) return status;
  StatusOr<WorldQuery> query = ParseWorldQuery(world);
  if (!query.ok()) return query.status();
  *request.mutable_rect() = RectToMessage(query->rect);
  return Status::Ok();
}

}  // namespace scallop::cli
