// Reading the bearer token from a call's metadata and checking its grant.
#include "server/call_authorization.h"

#include <cctype>
#include <string_view>

namespace scallop::server {

grpc::Status AuthorizeCall(const TokenTable* tokens, const grpc::ServerContextBase& context,
                           const RequestedWorld& world) {
  if (tokens == nullptr) return grpc::Status::OK;
  const auto& metadata = context.client_metadata();
  const auto header = metadata.find("authorization");
  if (header == metadata.end()) return AuthorizeBearer(tokens, nullptr, world);
  const std::string_view value(header->second.data(), header->second.size());
  return AuthorizeBearer(tokens, &value, world);
}

grpc::Status AuthorizeBearer(const TokenTable* tokens, const std::string_view* authorization,
                             const RequestedWorld& world) {
  if (tokens == nullptr) return grpc::Status::OK;
  const grpc::Status unauthenticated(
      grpc::StatusCode::UNAUTHENTICATED,
      "authorization: a valid bearer token is required (\"authorization: Bearer TOKEN\")");
  if (authorization == nullptr) return unauthenticated;
  const std::string_view value = *authorization;
  // The scheme is case-insensitive (RFC 7235); one space before the token.
  constexpr std::string_view kScheme = "bearer ";
  if (value.size() <= kScheme.size()) return unauthenticated;
  for (size_t i = 0; i < kScheme.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(value[i])) != kScheme[i]) return unauthenticated;
  }
  const TokenGrant* grant = tokens->Find(value.substr(kScheme.size()));
  if (grant == nullptr) return unauthenticated;
  if (grant->worlds.empty() || world.kind == RequestedWorld::Kind::kNone) return grpc::Status::OK;
  if (world.kind == RequestedWorld::Kind::kInline) {
    return {grpc::StatusCode::PERMISSION_DENIED,
            "world: this token may use only the named worlds it lists, not an inline world"};
  }
  if (!grant->worlds.contains(world.name)) {
    return {grpc::StatusCode::PERMISSION_DENIED,
            "world_name: this token may not use world '" + world.name + "'"};
  }
  return grpc::Status::OK;
}

}  // namespace scallop::server
