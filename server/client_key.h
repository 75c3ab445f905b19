// Who a call comes from, for per-client limits (rate_limiter.h, the
// admission budgets of in_flight_limit.h): its bearer token when the server
// checks tokens (the call was authorized with it), else its peer's address
// without the port, so one host's many connections count as one client.
// Behind a proxy every call has the proxy's address: give clients tokens.
#pragma once

#include <grpcpp/server_context.h>

#include <string>
#include <string_view>

namespace scallop::server {

// "token:<hash of the token>" when `tokens_checked`, else "peer:<address>",
// e.g. "peer:ipv4:127.0.0.1" or "peer:ipv6:[::1]". O(length of the token).
std::string ClientKey(const grpc::ServerContextBase& context, bool tokens_checked);

// The same from a peer string as gRPC gives it ("ipv4:10.0.0.7:51234").
std::string PeerKey(const std::string& peer);

// "token:<hash>" for the value of an authorization header.
std::string TokenKey(std::string_view authorization);

}  // namespace scallop::server
