// World: one fixed, infinite Poisson-disk point set, named by its parameters.
// A WorldSpec is what a caller typed or sent; a World is a spec that passed
// validation once, at the edge, so the core never checks it again.
// Points are a pure function of (World, generator version).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "scallop/base/status.h"
#include "scallop/sampling/sampler.h"

namespace scallop {

// Bumped on purpose whenever a change alters any world's points (tests pin
// golden hashes of fixed regions per algorithm to catch accidents).
inline constexpr uint32_t kGeneratorVersion = 3;

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

  friend bool operator==(const WorldSpec&, const WorldSpec&) = default;
};

// A valid world in canonical form: the only way to get one is Create (or the
// default, seed 0, d 1, A3), so every World the core receives is valid.
// A value type, cheap to copy; equal worlds have equal points.
class World {
 public:
  World() : World(WorldSpec{}) {}

  // INVALID_ARGUMENT naming the field: d outside [2^-256, 2^256] (where
  // squares of coordinates stay normal doubles); an algorithm other than a1,
  // a2, a3; density outside (1, 2] for a1 and a2; a generator version this
  // build does not have. Fields that do not affect the points are normalised
  // (density for A3), so equal worlds compare and hash equal.
  static StatusOr<World> Create(const WorldSpec& spec);

  const WorldSpec& spec() const { return spec_; }
  uint64_t seed() const { return spec_.seed; }
  double min_distance() const { return spec_.min_distance; }
  WorldAlgorithm algorithm() const { return spec_.algorithm; }
  double density() const { return spec_.density; }
  uint32_t generator_version() const { return spec_.generator_version; }

  // The same world with another seed: every seed is valid, so no check. For
  // series of unrelated worlds alike in everything else.
  World WithSeed(uint64_t seed) const;

  // A 64-bit digest of the canonical world, for seeds and cache keys:
  // HashWords({seed, bits(d), algorithm, bits(density), generator_version}).
  uint64_t fingerprint() const { return fingerprint_; }

  // "seed=7 d=1 algorithm=a3 version=3", for logs and errors.
  std::string Describe() const;

  friend bool operator==(const World& a, const World& b) { return a.spec_ == b.spec_; }

 private:
  // REQUIRES: spec valid and canonical.
  explicit World(const WorldSpec& spec);

  WorldSpec spec_;
  uint64_t fingerprint_;
};

}  // namespace scallop
