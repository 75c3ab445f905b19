// The options every command that talks to scallopd shares (--server, --world,
// --timeout), and the request fields they and the world options fill in.
#pragma once

#include <string>

#include "client/options/cli_fwd.h"
#include "client/options/connection_options.h"
#include "client/options/rect_option.h"
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

// Adds --encoding packed|exact|quantised (docs/wire.md) to a command that
// fetches points: how they travel, not what is printed, since the client
// library decodes them (quantised ones within 2^-13 d of the true points).
void AddEncodingOption(CLI::App& command, v1::PointEncoding& encoding);

// The inline world a request to scallopd carries, from --seed, --min-distance,
// --algorithm and --density, or with a radius field (a raster by the name the
// server loaded it under). Checked here as far as the client can (all but a
// raster's), so bad values exit 2 without a call.
StatusOr<v1::World> RemoteWorld(const WorldArguments& world);

// Sets the request's world: by name with --world, else inline (RemoteWorld).
template <typename Request>
Status SetRequestWorld(const RemoteArguments& remote, const WorldArguments& world,
                       Request& request) {
  if (!remote.world_name.empty()) {
    request.set_world_name(remote.world_name);
    return Status::Ok();
  }
  StatusOr<v1::World> message = RemoteWorld(world);
  if (!message.ok()) return message.status();
  *request.mutable_world() = std::move(*message);
  return Status::Ok();
}

// The request's layer filter from --layers (GetPoints, StreamPoints, Follow);
// the server checks the names against the world.
template <typename Request>
void SetRequestLayerFilter(const WorldArguments& world, Request& request) {
  for (const std::string& name : LayerFilterNames(world.layers)) request.add_layers(name);
}

// The request's world and --rect, checked as for `scallop plane`.
template <typename Request>
Status SetRequestWorldAndRect(const RemoteArguments& remote, const WorldArguments& world,
                              Request& request) {
  if (Status status = SetRequestWorld(remote, world, request); !status.ok()) return status;
  StatusOr<Rect> rect = ParseRect(world.rect, "--rect");
  if (!rect.ok()) return rect.status();
  *request.mutable_rect() = RectToMessage(*rect);
  return Status::Ok();
}

}  // namespace scallop::cli
