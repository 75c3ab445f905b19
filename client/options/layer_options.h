// The options that make a world layered (issue 19): --layer NAME=SPACING, repeated, where
// SPACING is a distance or a radius field (noise:R_MIN,R_MAX,FREQUENCY[,OCTAVES[,SEED]] or
// raster:FILE:R_MIN,R_MAX[:X,Y[:PIXEL]]); --exclusion NAME,NAME=DISTANCE, repeated; and
// --layers NAME[,NAME], which layers to print. Shared by every command that takes a world.
#pragma once

#include <string>
#include <vector>

#include "client/options/cli_fwd.h"
#include "scallop/base/status.h"
#include "scallop/plane/layer_spec.h"
#include "scallop/plane/plane_engine.h"
#include "scallop/plane/world.h"
#include "scallop/v1/scallop.pb.h"

namespace scallop::cli {

// The options as typed.
struct LayerArguments {
  std::vector<std::string> layers;      // NAME=SPACING each
  std::vector<std::string> exclusions;  // NAME,NAME=DISTANCE each
  std::string filter;                   // NAME[,NAME]; empty: every layer
};

// Adds the layer options to `command`, storing into `arguments` (which must outlive parsing).
// --layer excludes --min-distance and the radius-field options (each layer has its own), and
// --exclusion and --layers need --layer.
void AddLayerOptions(CLI::App& command, LayerArguments& arguments);

bool HasLayers(const LayerArguments& arguments);

// The layers as specs, a raster's PNG read from its file (a local run). INVALID_ARGUMENT naming
// --layer and the text for a malformed one ("--layer: expected NAME=SPACING, got 'trees'"); a
// field's errors as the field options give them, led by the layer ("--layer rocks: field.r_max
// ..."). The names and spacings' ranges are World::Create's to judge.
StatusOr<std::vector<LayerSpec>> ParseLayers(const LayerArguments& arguments);

// The layers as a request to scallopd carries them: a raster layer's FILE is the name of a
// raster the server loaded (the server judges it), the others as ParseLayers reads them
// (checked here). Errors as ParseLayers'.
StatusOr<std::vector<v1::Layer>> ParseRemoteLayers(const LayerArguments& arguments);

// The exclusions as specs; INVALID_ARGUMENT naming --exclusion for a malformed one.
StatusOr<std::vector<LayerExclusionSpec>> ParseExclusions(const LayerArguments& arguments);

// The layers --layers names in `world` (every layer when empty). INVALID_ARGUMENT naming
// --layers for an unknown name, or names given for a world without layers.
StatusOr<LayerMask> ParseLayerFilter(const LayerArguments& arguments, const World& world);

// The world whose noise basis `nearest` and `noise` compute: `world` itself without layers (no
// --layers allowed), else the world of the one layer --layers names (required), as scallopd's
// Nearest answers for NearestRequest.layer. INVALID_ARGUMENT naming --layers otherwise.
StatusOr<World> NoiseBasisWorld(const LayerArguments& arguments, const World& world);

// --layers as names, for a request's filter (GetPointsRequest.layers), which the server checks.
std::vector<std::string> LayerFilterNames(const LayerArguments& arguments);

// The one layer --layers names, for Nearest and NoiseGrid (NearestRequest.layer): empty when
// not given; INVALID_ARGUMENT naming --layers for more than one.
StatusOr<std::string> SingleLayerName(const LayerArguments& arguments);

}  // namespace scallop::cli
