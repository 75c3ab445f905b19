// A request's layers: the filter of GetPoints, StreamPoints and Follow (`layers`, by name) and
// the one layer Nearest and NoiseGrid answer for (`layer`), checked against the world.
#pragma once

#include <google/protobuf/repeated_ptr_field.h>
#include <grpcpp/support/status.h>

#include <string>

#include "scallop/plane/plane_engine.h"
#include "scallop/plane/world.h"

namespace scallop::server {

// The layers `names` asks for: every layer when empty (kAllLayers). INVALID_ARGUMENT naming
// `field` for a name the world has not (the name escaped and cut, the world's names listed) or
// for names on a world without layers.
grpc::Status LayerFilterOf(const World& world,
                           const google::protobuf::RepeatedPtrField<std::string>& names,
                           const char* field, LayerMask& mask);

// The layer `name` names: -1 for a world without layers (`name` must be empty); for a layered
// world its number. INVALID_ARGUMENT naming `field` when a layered world's is missing or
// unknown, or a world without layers is given one.
grpc::Status LayerChoiceOf(const World& world, const std::string& name, const char* field,
                           int& layer);

// The mask with only the world's layers' bits (kAllLayers for a world without layers), so
// that equal filters compare equal.
LayerMask NormalisedLayerMask(const World& world, LayerMask mask);

}  // namespace scallop::server
