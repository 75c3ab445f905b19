// The worlds a request may name: inline in the request, by a configured name,
// or (neither) the server's default; and the rasters loaded at start, which
// raster radius fields name. The configured worlds and rasters are immutable
// after start, so every request thread reads them without locking; inline
// raster worlds are remembered in a small locked cache (below).
#pragma once

#include <grpcpp/support/status.h>

#include <deque>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "raster_catalog.h"
#include "scallop/plane/world.h"
#include "scallop/v1/scallop.pb.h"
#include "world_messages.h"

namespace scallop::server {

struct ResolvedWorld {
  World world;       // valid and canonical
  std::string name;  // the configured name, empty for an inline world
  // A configured world's Describe(), made once by the registry (which owns
  // it and outlives every call): a call's log line needs no formatting of
  // its world. Null for an inline world.
  const std::string* description = nullptr;
  // A configured world's ToMessage, serialized once by the registry, for
  // answers written as bytes (packed_answer.h). Null for an inline world.
  const std::string* message = nullptr;
};

class WorldRegistry {
 public:
  WorldRegistry(std::map<std::string, World> worlds, std::string default_name,
                RasterCatalog rasters = {})
      : worlds_(std::move(worlds)),
        default_name_(std::move(default_name)),
        rasters_(std::move(rasters)) {
    for (const auto& [name, world] : worlds_) {
      texts_.emplace(name, WorldTexts{world.Describe(), ToMessage(world).SerializeAsString()});
    }
  }

  // The request's world: INVALID_ARGUMENT naming the world.* field for a bad
  // inline world (an unknown raster name included), NOT_FOUND naming
  // world_name for an unknown name.
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

  // The world as answers carry it: a raster field by its name and pixel hash.
  v1::World ToMessage(const World& world) const {
    return scallop::WorldToMessage(world, &rasters_);
  }

  const std::string& default_name() const { return default_name_; }
  std::vector<std::string> names() const;
  const std::map<std::string, World>& worlds() const { return worlds_; }
  const RasterCatalog& rasters() const { return rasters_; }
  // A stable text of every configured world, for deriving the page-token key.
  std::string Fingerprint() const;

  // Inline raster worlds remembered: building one reads every pixel (its
  // slope bound and mask table, O(pixels), tens of milliseconds for a large
  // raster), so a client sending the same world again skips that. At most
  // this many, the oldest forgotten first; each shares its raster's pixels
  // and holds its own mask table (up to 64 MiB for a 2^24-pixel raster).
  static constexpr size_t kInlineRasterWorlds = 8;

 private:
  grpc::Status ResolveInline(const v1::World& message, ResolvedWorld& resolved) const;
  grpc::Status ResolveName(const std::string& name, ResolvedWorld& resolved) const;

  std::map<std::string, World> worlds_;
  // A configured world's texts, made once (ResolvedWorld says why).
  struct WorldTexts {
    std::string description;  // Describe()
    std::string message;      // ToMessage, serialized
  };
  std::map<std::string, WorldTexts> texts_;  // by name, as worlds_
  std::string default_name_;
  RasterCatalog rasters_;
  // Serialized message -> world, and the keys oldest first.
  mutable std::mutex inline_mutex_;
  mutable std::map<std::string, World> inline_rasters_;
  mutable std::deque<std::string> inline_order_;
};

}  // namespace scallop::server
