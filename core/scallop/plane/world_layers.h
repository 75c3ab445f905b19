// A layered world's layers once validated (issue 19): each layer's own World, the order layers
// are generated in, and the exclusion matrix D. World::Create builds them; the plane engine
// generates each layer as a world of its own whose regions keep clear of the earlier layers'
// points. docs/design.md, "Layers", has the argument.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "scallop/base/status.h"
#include "scallop/plane/world.h"
#include "scallop/sampling/layered_sampler.h"

namespace scallop {

// The stream a later layer's seed is hashed with: HashWords({world seed, kLayerSeedStream, g})
// for the layer generated g-th (g >= 1; the first keeps the world's seed).
inline constexpr uint64_t kLayerSeedStream = 0x4c41594552ULL;  // "LAYER"

// What the world of a layer generated after others keeps clear of: the worlds of the layers
// generated before it, first generated first, and the distance D to each (0: none).
struct EarlierLayers {
  std::vector<World> worlds;
  std::vector<double> distances;
  // The largest of `distances`.
  double largest_distance = 0.0;
};

// Immutable; shared by every copy of its World.
class WorldLayers {
 public:
  // The layered World for `spec` (spec.layers not empty). INVALID_ARGUMENT naming the field:
  //  - world.layers: more than kMaxLayers;
  //  - world.radius_field: set (each layer gives its own);
  //  - world.algorithm: not a3 with more than one layer (the later layers grow by A3's rule);
  //  - world.layers[k].name: empty, longer than 64, a character outside [A-Za-z0-9_.-], or
  //    the name of an earlier layer;
  //  - world.layers[k].min_distance, world.layers[k].radius_field.*: what World::Create says
  //    of a plain world's spacing, renamed;
  //  - world.exclusions[n].first / .second: no layer of that name; world.exclusions[n]: a layer
  //    paired with itself (its own spacing is its radius), the pair given before with another
  //    distance (the matrix must be symmetric, so (a, b) and (b, a) are one entry);
  //  - world.exclusions[n].distance: negative, NaN or infinite, or above kMaxExclusionInRMax
  //    times the larger of the two layers' largest spacings.
  // Cost: each layer's World::Create (a raster's O(pixels)), O(layers^2) for the matrix.
  static StatusOr<World> Create(const WorldSpec& spec);

  int count() const { return static_cast<int>(names_.size()); }
  // Layers are numbered in the order the spec gives them; the number is a point's layer.
  const std::string& name(int layer) const { return names_[static_cast<size_t>(layer)]; }
  // The layer numbered so, or -1.
  int LayerNamed(std::string_view name) const;
  // The world whose points are the layer's: its ids, regions and cache entries. The first
  // layer generated is the plain world of its spacing with the world's seed.
  const World& world(int layer) const { return worlds_[static_cast<size_t>(layer)]; }
  // D[a][b]: for a != b the least distance between their points; for a == b the layer's largest
  // spacing (its own rule is its radius, or max(R(p), R(q)) for a field).
  double exclusion(int a, int b) const {
    return matrix_[static_cast<size_t>(a) * names_.size() + static_cast<size_t>(b)];
  }
  // Whether D[a][b] was given (otherwise it is the default below).
  bool exclusion_given(int a, int b) const {
    return given_[static_cast<size_t>(a) * names_.size() + static_cast<size_t>(b)];
  }
  // Layer numbers, first generated first: by decreasing largest spacing, ties in the spec's
  // order.
  const std::vector<int>& generation_order() const { return order_; }
  // The largest spacing of any layer, and the largest D between two layers.
  double largest_spacing() const { return largest_spacing_; }
  double largest_exclusion() const { return largest_exclusion_; }

 private:
  std::vector<std::string> names_;
  std::vector<World> worlds_;
  std::vector<double> matrix_;
  std::vector<bool> given_;
  std::vector<int> order_;
  double largest_spacing_ = 0.0;
  double largest_exclusion_ = 0.0;
};

// The default D[a][b] for a != b (after Wei, "Multi-class blue noise sampling", SIGGRAPH 2010):
// with r_c each layer's largest spacing and C the layers generated no later than the later of
// a and b, D = (sum over c in C of r_c^-2)^(-1/2): the spacing of one Poisson-disk set as dense
// as those layers together. Never above the smaller of r_a and r_b. `spacings` in generation
// order; `later` the generation position of the later layer.
double DefaultExclusion(const std::vector<double>& spacings, int later);

// The layers of `layers` as a bounded run on `domain` samples them (SampleLayers): each layer's
// spacing or field and its world's seed, the generation order and the matrix. The options point
// into `layers`' fields, so `layers` must outlive them. Not the plane's points: those are a
// world's, this is one rectangle sampled on its own (docs/design.md, "On a bounded rectangle").
LayeredSamplerOptions BoundedLayersOn(const WorldLayers& layers, const Rect& domain);

}  // namespace scallop
