// Layer names in requests, checked against the world's layers.
#include "server/layer_choice.h"

#include "scallop/plane/world_layers.h"
#include "server/client_text.h"

namespace scallop::server {
namespace {

std::string LayerNamesText(const WorldLayers& layers) {
  std::string text;
  for (int k = 0; k < layers.count(); ++k) text += (k == 0 ? "" : ", ") + layers.name(k);
  return text;
}

grpc::Status Invalid(const std::string& message) {
  return {grpc::StatusCode::INVALID_ARGUMENT, message};
}

}  // namespace

grpc::Status LayerFilterOf(const World& world,
                           const google::protobuf::RepeatedPtrField<std::string>& names,
                           const char* field, LayerMask& mask) {
  mask = kAllLayers;
  if (names.empty()) return grpc::Status::OK;
  const WorldLayers* layers = world.layers();
  if (layers == nullptr) {
    return Invalid(std::string(field) + ": the world has no layers; leave it empty");
  }
  mask = 0;
  for (const std::string& name : names) {
    const int layer = layers->LayerNamed(name);
    if (layer < 0) {
      return Invalid(std::string(field) + ": no layer named " + QuotedClientText(name) +
                     " (the world's: " + LayerNamesText(*layers) + ")");
    }
    mask |= LayerMask{1} << layer;
  }
  return grpc::Status::OK;
}

grpc::Status LayerChoiceOf(const World& world, const std::string& name, const char* field,
                           int& layer) {
  layer = -1;
  const WorldLayers* layers = world.layers();
  if (layers == nullptr) {
    if (name.empty()) return grpc::Status::OK;
    return Invalid(std::string(field) + ": the world has no layers; leave it empty");
  }
  if (name.empty()) {
    return Invalid(std::string(field) +
                   ": required for a layered world, the layer to answer for (the world's: " +
                   LayerNamesText(*layers) + ")");
  }
  layer = layers->LayerNamed(name);
  if (layer < 0) {
    return Invalid(std::string(field) + ": no layer named " + QuotedClientText(name) +
                   " (the world's: " + LayerNamesText(*layers) + ")");
  }
  return grpc::Status::OK;
}

LayerMask NormalisedLayerMask(const World& world, LayerMask mask) {
  const WorldLayers* layers = world.layers();
  if (layers == nullptr) return kAllLayers;
  return mask & ((LayerMask{1} << layers->count()) - 1);
}

}  // namespace scallop::server
