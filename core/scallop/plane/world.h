// World: one fixed, infinite Poisson-disk point set, named by its parameters.
// A WorldSpec is what a caller typed or sent; a World is a spec that passed
// validation once, at the edge, so the core never checks it again.
// Points are a pure function of (World, generator version).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scallop/base/status.h"
#include "scallop/field/radius_field.h"
#include "scallop/geometry/vec2.h"
#include "scallop/plane/layer_spec.h"
#include "scallop/sampling/sampler.h"

namespace scallop {

// Bumped on purpose whenever a change alters any world's points (tests pin
// golden hashes of fixed regions per algorithm to catch accidents).
inline constexpr uint32_t kGeneratorVersion = 4;

// The samplers a world can grow its regions with: those that can constrain
// their output by fixed points (the baselines cannot). The values are hashed
// into every world's fingerprint, so they never change.
enum class WorldAlgorithm : uint8_t { kA1 = 0, kA2 = 1, kA3 = 2 };

// "a1", "a2", "a3".
std::string_view WorldAlgorithmName(WorldAlgorithm algorithm);
// INVALID_ARGUMENT naming `field` for anything but a1, a2 or a3.
StatusOr<WorldAlgorithm> ParseWorldAlgorithm(std::string_view name,
                                             std::string_view field = "world.algorithm");
// True for the algorithms whose density the outer radius r' tunes (A1, A2).
bool UsesDensity(WorldAlgorithm algorithm);
// The bounded sampler that grows the world's regions.
Algorithm SamplerAlgorithm(WorldAlgorithm algorithm);

// A world's parameters as given, not yet checked.
struct WorldSpec {
  uint64_t seed = 0;
  // Minimum distance d between any two points, in [2^-256, 2^256].
  double min_distance = 1.0;
  WorldAlgorithm algorithm = WorldAlgorithm::kA3;
  // r' / 2r in (1, 2] for A1 and A2; ignored (and normalised to 2) for A3.
  double density = 2.0;
  uint32_t generator_version = kGeneratorVersion;
  // The spacing R(x) wanted at x (issue 24; docs/design.md, "Radius fields"). Absent: the
  // constant spacing min_distance, as every world before fields (their points, ids and
  // fingerprints are unchanged). Present: min_distance is ignored and normalised to r_min; a
  // constant field is the plain world with min_distance = r.
  std::optional<RadiusFieldSpec> radius_field = std::nullopt;
  // Layers (issue 19; docs/design.md, "Layers"): empty for a world of one kind of point, as
  // every world before layers. Given, each layer has its own spacing (min_distance and
  // radius_field above are then ignored), and `exclusions` the distances kept between layers.
  std::vector<LayerSpec> layers = {};
  std::vector<LayerExclusionSpec> exclusions = {};
};

class WorldLayers;
struct EarlierLayers;

// A valid world in canonical form: the only way to get one is Create (or the
// default, seed 0, d 1, A3), so every World the core receives is valid.
// A value type, cheap to copy; equal worlds have equal points.
class World {
 public:
  World() : World(WorldSpec{}, nullptr) {}

  // INVALID_ARGUMENT naming the field: d outside [2^-256, 2^256] (where
  // squares of coordinates stay normal doubles); an algorithm other than a1,
  // a2, a3; density outside (1, 2] for a1 and a2; a generator version this
  // build does not have. Fields that do not affect the points are normalised
  // (density for A3), so equal worlds compare and hash equal.
  // A radius field is checked by RadiusField::Create; its errors are renamed
  // into the world's namespace: the field's own name less "field.", after
  // "world.radius_field." (world.radius_field.r_min, world.radius_field.frequency,
  // world.radius_field.raster.pixel_size). A field world must use a3
  // ("world.algorithm": only A3's growth takes a field). A constant field is
  // normalised to the plain world with d = r, whose points it has; for other
  // fields min_distance is normalised to r_min. Cost: a raster's O(pixels).
  // Layers are checked by WorldLayers' rules (world_layers.h): their count, names, spacings
  // (errors named world.layers[k]....) and exclusions (world.exclusions[n]....); a layered
  // world's min_distance is normalised to the smallest r_min of its layers (the rectangle
  // rule's unit), and it may not have a radius_field of its own.
  static StatusOr<World> Create(const WorldSpec& spec);

  const WorldSpec& spec() const { return spec_; }
  uint64_t seed() const { return spec_.seed; }
  double min_distance() const { return spec_.min_distance; }
  WorldAlgorithm algorithm() const { return spec_.algorithm; }
  double density() const { return spec_.density; }
  uint32_t generator_version() const { return spec_.generator_version; }

  // The world's radius field; null for a constant-spacing world (including one
  // given a constant field). Shared by every copy of the World.
  const RadiusField* radius_field() const { return field_.get(); }
  // The spacing wanted at x: R(x) for a field world, d otherwise.
  double SpacingAt(Vec2 x) const { return field_ ? field_->Evaluate(x) : spec_.min_distance; }
  // The largest spacing anywhere: r_max for a field world, d otherwise. Region
  // sizes and neighbour reaches scale with it.
  double max_spacing() const { return field_ ? field_->r_max() : spec_.min_distance; }

  // A layered world's layers (each a World of its own, the order they are generated in, the
  // exclusion matrix); null for a world of one kind. The points of a layered world are its
  // layers' points: query those worlds (PlaneEngine does).
  const WorldLayers* layers() const { return layers_.get(); }
  // For the world of a layer generated after others: those layers' worlds and the distance
  // this layer keeps from each; null for every other world. Its regions read those layers.
  const EarlierLayers* earlier_layers() const { return earlier_.get(); }

  // The same world with another seed: every seed is valid, so no check. For
  // series of unrelated worlds alike in everything else.
  // A layered world gets new seeds for all its layers. REQUIRES: not a layer's world
  // (earlier_layers() null).
  World WithSeed(uint64_t seed) const;

  // A 64-bit digest of the canonical world, for seeds and cache keys:
  // HashWords({seed, bits(d), algorithm, bits(density), generator_version}),
  // and for a field world HashWords({..., generator_version, field.Fingerprint()})
  // with d = r_min (so a raster's pixels enter, never its address). A layered world and a
  // later layer's world hash more (world_layers.h); the first layer's world is a plain world.
  uint64_t fingerprint() const { return fingerprint_; }

  // "seed=7 d=1 algorithm=a3 version=3", for logs and errors; a field world
  // adds its field: "field=noise r=[1,8] frequency=0.01 octaves=3 gain=0.5
  // noise_seed=4" or "field=raster r=[1,8] raster=640x480x16 origin=(0,0)
  // pixel_size=2 field_hash=<hex of the field's fingerprint, pixels included>".
  std::string Describe() const;

  // Equal parameters; fields compare by their fingerprints (a raster by its
  // pixels' hash, not by which copy of the image it holds), layered worlds and
  // layers' worlds by theirs.
  friend bool operator==(const World& a, const World& b);

 private:
  friend class WorldLayers;

  // REQUIRES: spec valid and canonical; field built from spec.radius_field.
  World(const WorldSpec& spec, std::shared_ptr<const RadiusField> field);

  // Create for a world without layers: its checks and normal form.
  static StatusOr<World> CreatePlain(const WorldSpec& spec);

  WorldSpec spec_;
  std::shared_ptr<const RadiusField> field_;
  std::shared_ptr<const WorldLayers> layers_;
  std::shared_ptr<const EarlierLayers> earlier_;
  uint64_t fingerprint_;
};

}  // namespace scallop
