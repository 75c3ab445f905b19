// Resolution of a request's world: inline, by name, or the default.
#include "server/world_registry.h"

#include "server/client_text.h"
#include "server/status_mapping.h"
#include "world_messages.h"

namespace scallop::server {

grpc::Status WorldRegistry::ResolveInline(const v1::World& message, ResolvedWorld& resolved) const {
  StatusOr<World> world = WorldFromMessage(message);
  if (!world.ok()) return ToGrpcStatus(world.status());
  resolved = {*world, ""};
  return grpc::Status::OK;
}

grpc::Status WorldRegistry::ResolveName(const std::string& name, ResolvedWorld& resolved) const {
  const auto found = worlds_.find(name);
  if (found == worlds_.end()) {
    std::string known;
    for (const auto& [known_name, world] : worlds_)
      known += (known.empty() ? "" : ", ") + known_name;
    // The name is the client's: escaped and cut, as any client text.
    return {grpc::StatusCode::NOT_FOUND, "world_name: no world named " + QuotedClientText(name) +
                                             " on this server (configured: " + known + ")"};
  }
  resolved = {found->second, name};
  return grpc::Status::OK;
}

std::vector<std::string> WorldRegistry::names() const {
  std::vector<std::string> names;
  for (const auto& [name, world] : worlds_) names.push_back(name);
  return names;
}

std::string WorldRegistry::Fingerprint() const {
  std::string text = "default=" + default_name_;
  for (const auto& [name, world] : worlds_) text += ";" + name + "=" + world.Describe();
  return text;
}

}  // namespace scallop::server
