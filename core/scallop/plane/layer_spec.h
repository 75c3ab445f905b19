// The layers of a world as a caller gives them (issue 19): each a named kind of object with its
// own spacing, and the distances kept between kinds. Plain parameters, checked by World::Create;
// world_layers.h holds the validated form. docs/design.md, "Layers".
#pragma once

#include <optional>
#include <string>

#include "scallop/field/radius_field.h"

namespace scallop {

// At most this many layers in a world. The exclusion matrix is 16 x 16, and a layer's region
// reads every earlier layer, so the cost of the last layer's cold region grows with the count.
inline constexpr int kMaxLayers = 16;
// A layer's name: 1 to 64 characters of [A-Za-z0-9_.-], so that it can stand in CSV, YAML and
// command lines unquoted.
inline constexpr size_t kMaxLayerNameLength = 64;
// An exclusion distance may be at most this many times the larger of the two layers' largest
// spacings: a region of the later layer reads the earlier one's points within that distance of
// itself, so the distance bounds how far a query reaches (the locality bound).
inline constexpr double kMaxExclusionInRMax = 4.0;

struct LayerSpec {
  std::string name;
  // The layer's own spacing, as WorldSpec::min_distance and WorldSpec::radius_field: a constant
  // d, or a radius field (then min_distance is ignored).
  double min_distance = 1.0;
  std::optional<RadiusFieldSpec> radius_field = std::nullopt;
};

// D[first][second] = D[second][first] = distance: the least distance between a point of one
// layer and a point of the other. Pairs not given take the default (world_layers.h).
struct LayerExclusionSpec {
  std::string first;
  std::string second;
  double distance = 0.0;
};

}  // namespace scallop
