#include "server/client_key.h"

#include <fmt/format.h>

#include <functional>
#include <string_view>

namespace scallop::server {

std::string PeerKey(const std::string& peer) {
  // "ipv4:HOST:PORT", "ipv6:[HOST]:PORT": drop the last ":PORT". Unix
  // sockets ("unix:/path") have no port and stay whole.
  const bool has_port = peer.starts_with("ipv4:") || peer.starts_with("ipv6:");
  const size_t colon = peer.rfind(':');
  return "peer:" + (has_port && colon > 5 ? peer.substr(0, colon) : peer);
}

std::string TokenKey(std::string_view authorization) {
  return fmt::format("token:{:016x}", std::hash<std::string_view>{}(authorization));
}

std::string ClientKey(const grpc::ServerContextBase& context, bool tokens_checked) {
  if (tokens_checked) {
    const auto& metadata = context.client_metadata();
    if (const auto header = metadata.find("authorization"); header != metadata.end()) {
      return TokenKey(std::string_view(header->second.data(), header->second.size()));
    }
  }
  return PeerKey(context.peer());
}

}  // namespace scallop::server
