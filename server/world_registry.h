// The worlds a request may name: inline in the request, by a configured name,
// or (neither) the server's default. Immutable after start, so every request
// thread reads it without locking.
#pragma once

#include <grpcpp/support/status.h>

#include <map>
#include <string>
#include <vector>

#include "scallop/plane/world.h"
#include "scallop/v1/scallop.pb.h"

namespace scallop::server {

struct ResolvedWorld {
  World world;       // valid and canonical
  std::string name;  // the configured name, empty for an inline world
};

class WorldRegistry {
 public:
  WorldRegistry(std::map<std::string, World> worlds, std::string default_name)
      : worlds_(std::move(worlds)), default_name_(std::move(default_name)) {}

  // The request's world: INVALID_ARGUMENT naming the world.* field for a bad
  // inline world, NOT_FOUND naming world_name for an unknown name.
  template <typename Request>
  grpc::Status Resolve(const Request& request, ResolvedWorld& resolved) const {
    switch (request.world_choice_case()) {
      case Request::kWorld:
        return ResolveInline(request.world(), resolved);
      case Request::kWorldName:
        return ResolveName(request.world_name(), resolved);
      default:
        return ResolveName(default_name_, resolved);
    }
  }

  const std::string& default_name() const { return default_name_; }
  std::vector<std::string> names() const;
  // A stable text of every configured world, for deriving the page-token key.
  std::string Fingerprint() const;

 private:
  grpc::Status ResolveInline(const v1::World& message, ResolvedWorld& resolved) const;
  grpc::Status ResolveName(const std::string& name, ResolvedWorld& resolved) const;

  std::map<std::string, World> worlds_;
  std::string default_name_;
};

}  // namespace scallop::server
