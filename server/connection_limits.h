// What one connection may hold and how long it lives: gRPC channel arguments
// set from the configuration (server_config.h, "Connections"), so that idle
// or dead connections, ping floods and connections with thousands of calls
// cannot pile up. See docs/deploy.md for what each is for behind a balancer.
#pragma once

#include <grpcpp/server_builder.h>

#include "server/server_config.h"

namespace scallop::server {

// Sets on `builder`: concurrent streams per connection; server keepalive
// pings and their timeout; the least interval between client pings (and two
// strikes); maximum idle time and age (with its grace) of a connection.
void ApplyConnectionLimits(const ServerConfig& config, grpc::ServerBuilder& builder);

}  // namespace scallop::server
