// Resolution of a request's world: inline, by name, or the default.
#include "server/world_registry.h"

#include <algorithm>

#include "server/client_text.h"
#include "server/status_mapping.h"

namespace scallop::server {

grpc::Status WorldRegistry::ResolveInline(const v1::World& message, ResolvedWorld& resolved) const {
  // A raster layer costs its pixels as a raster world does.
  const bool raster =
      message.radius_field().has_raster() ||
      std::any_of(message.layers().begin(), message.layers().end(),
                  [](const v1::Layer& layer) { return layer.radius_field().has_raster(); });
  std::string key;
  if (raster) {
    // Equal messages serialize alike: the fields are scalars written in field order.
    key = message.SerializeAsString();
    std::lock_guard lock(inline_mutex_);
    if (const auto found = inline_rasters_.find(key); found != inline_rasters_.end()) {
      resolved = {found->second, ""};
      return grpc::Status::OK;
    }
  }
  StatusOr<World> world = WorldFromMessage(message, &rasters_);
  if (!world.ok()) return ToGrpcStatus(world.status());
  if (raster) {
    std::lock_guard lock(inline_mutex_);
    if (inline_rasters_.emplace(key, *world).second) {
      inline_order_.push_back(key);
      if (inline_order_.size() > kInlineRasterWorlds) {
        inline_rasters_.erase(inline_order_.front());
        inline_order_.pop_front();
      }
    }
  }
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
  const WorldTexts& texts = texts_.at(name);
  resolved = {found->second, name, &texts.description, &texts.message};
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
