// Bounded sampling of several object layers (issue 19): each layer keeps its own spacing (a
// distance or a radius field), and a point of layer a keeps D[a][b] from every point of layer b.
// Layers are sampled one after another, each maximal in what the earlier ones leave: the
// earlier layers' points are exclusion disks of radius D for the later ones (SamplingProblem::
// exclusions), as a layered world's regions have them on the plane (docs/design.md, "Layered
// worlds", "On a bounded rectangle").
#pragma once

#include <cstdint>
#include <vector>

#include "scallop/base/status.h"
#include "scallop/field/radius_field.h"
#include "scallop/geometry/rect.h"
#include "scallop/geometry/vec2.h"

namespace scallop {

// One layer of a bounded layered run.
struct BoundedLayer {
  double min_distance = 1.0;           // a constant layer's spacing d (ignored with a field)
  const RadiusField* field = nullptr;  // a field layer's R (not owned), or null: constant
  uint64_t seed = 0;                   // the layer's own random stream
};

struct LayeredSamplerOptions {
  // Half-open [x0, x1) x [y0, y1), every layer's.
  Rect domain;
  // Numbered as the points' layers; at most 255.
  std::vector<BoundedLayer> layers;
  // The order the layers are sampled in: a permutation of their numbers, first sampled first.
  std::vector<int> order;
  // D[a * layers.size() + b] for a != b: the least distance between points of layers a and b,
  // symmetric, 0 for none (the diagonal is not read: a layer's own spacing is its rule).
  std::vector<double> exclusions;
};

struct LayeredPoints {
  std::vector<Vec2> positions;  // by layer in sampling order, each layer in generation order
  std::vector<uint8_t> layers;  // layers[k] is the layer of positions[k]
};

// Checks every field and returns a status naming the first bad one: INVALID_ARGUMENT for no
// layers or more than 255 ("layers"), an order that is not a permutation ("order"), a matrix of
// the wrong size or an entry that is negative, NaN, infinite, asymmetric or above
// kMaxExclusionInRMax times the larger of its two layers' largest spacings ("exclusions[n]"),
// and what Sample (A3) or SampleField say of the domain and a layer's spacing, led by the layer
// ("layers[2]: min_distance ..."); OUT_OF_RANGE as they give it.
Status ValidateLayeredSamplerOptions(const LayeredSamplerOptions& options);

// Validates, then samples. Pure: the same options give the same bits. Each layer is sampled on
// the domain by A3 (a constant layer) or the field sampler (a field layer), seeded by its own
// seed, with the points of the layers sampled before it as disks of radius D it may not enter.
// Guarantees, on the returned doubles: within a layer, what Sample's A3 (every pair at least d
// apart) or SampleField (max(R(p), R(q))) guarantees; across layers a and b, every pair at
// least D[a][b] apart (dx^2 + dy^2 >= D^2); each layer maximal in the domain less the earlier
// layers' disks, as its sampler is in a domain.
// A constant layer sampled first gives exactly Sample's A3 points for its seed and the domain.
// Cost: each layer's sampler on the domain, plus, for a constant layer after others, the disks'
// arcs cut from its candidates' circles (docs/performance.md, "Layered worlds": against the
// studios' way of pruned passes).
StatusOr<LayeredPoints> SampleLayers(const LayeredSamplerOptions& options);

}  // namespace scallop
