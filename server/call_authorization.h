// Whether a call may proceed: its bearer token (UNAUTHENTICATED without a
// known one) and the world it asks for (PERMISSION_DENIED outside its
// token's worlds). The health service is not ours, so it stays open.
#pragma once

#include <grpcpp/server_context.h>

#include <string>
#include <string_view>

#include "server/token_table.h"

namespace scallop::server {

// The world a request asks for, as a token's world list sees it.
struct RequestedWorld {
  enum class Kind { kNone, kNamed, kInline };
  Kind kind = Kind::kNone;  // kNone: the call concerns no world (GetServerInfo)
  std::string name;         // kNamed: world_name, or the default world's name when unset
};

template <typename Request>
RequestedWorld RequestedWorldOf(const Request& request, const std::string& default_name) {
  switch (request.world_choice_case()) {
    case Request::kWorld:
      return {.kind = RequestedWorld::Kind::kInline, .name = {}};
    case Request::kWorldName:
      return {.kind = RequestedWorld::Kind::kNamed, .name = request.world_name()};
    default:
      return {.kind = RequestedWorld::Kind::kNamed, .name = default_name};
  }
}

// OK when `tokens` is null (no tokens configured). Otherwise the call's
// "authorization: Bearer TOKEN" metadata must name a token of the table
// (UNAUTHENTICATED, without saying whether it was missing or wrong, beyond
// that), and its grant must allow `world` (PERMISSION_DENIED naming it).
// Cost: one SHA-256 and a compare a configured token.
grpc::Status AuthorizeCall(const TokenTable* tokens, const grpc::ServerContextBase& context,
                           const RequestedWorld& world);

// The same check on the value of an "authorization" header (null: none was
// sent), for callers that are not gRPC calls (the HTTP tiles).
grpc::Status AuthorizeBearer(const TokenTable* tokens, const std::string_view* authorization,
                             const RequestedWorld& world);

}  // namespace scallop::server
