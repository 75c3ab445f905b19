// Where `scallop analyze`'s sets of a layered world come from: the world's points in a --rect
// window (the plane), or the layers sampled on a --domain alone, one after another (a3,
// SampleLayers) or jointly by Wei's multi-class dart throwing (wei), the scheme the ordered
// layers are compared against (docs/quality.md, "Layered worlds").
#pragma once

#include <string>
#include <vector>

#include "scallop/base/status.h"
#include "scallop/geometry/rect.h"
#include "scallop/plane/plane_engine.h"
#include "scallop/plane/world.h"

namespace scallop::cli {

// Set s is the world reseeded to seed + s, queried on `window` by `engine`.
StatusOr<std::vector<PlanePoints>> WorldLayerSets(const World& world, const Rect& window, int sets,
                                                  PlaneEngine& engine);

// Set s is the world reseeded to seed + s, its layers sampled on `domain` alone by `algorithm`:
// "a3", the layers in generation order (SampleLayers); or "wei", Wei's multi-class darts
// (multiclass_darts.h) aiming at the counts the a3 run of the same seed reaches, so that both
// schemes are judged at the same densities, and stopping after 100,000 rejected darts in a row.
// The sets carry no ids. REQUIRES: world.layers(). Rejects (INVALID_ARGUMENT) another
// algorithm ("--algorithm"), field layers with wei, and what the samplers reject ("--domain").
StatusOr<std::vector<PlanePoints>> BoundedLayerSets(const World& world, const Rect& domain,
                                                    const std::string& algorithm, int sets);

}  // namespace scallop::cli
