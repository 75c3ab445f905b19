// World: the parameters that name one fixed, infinite Poisson-disk point set.
// Points are a pure function of (World, generator version).
#pragma once

#include <cstdint>
#include <string>

#include "scallop/base/status.h"
#include "scallop/sampling/sampler.h"

namespace scallop {

// Bumped on purpose whenever a change alters any world's points (tests pin
// golden hashes of fixed regions per algorithm to catch accidents).
inline constexpr uint32_t kGeneratorVersion = 3;

struct World {
  uint64_t seed = 0;
  // Minimum distance d between any two points, > 0.
  double min_distance = 1.0;
  // kA1, kA2 or kA3 (the baselines cannot constrain their output by fixed points).
  Algorithm algorithm = Algorithm::kA3;
  // r' / 2r in (1, 2] for A1 and A2; ignored (and normalised to 2) for A3.
  double density = 2.0;
  uint32_t generator_version = kGeneratorVersion;

  friend bool operator==(const World&, const World&) = default;
};

// INVALID_ARGUMENT naming the field: d outside [2^-256, 2^256] (where squares
// of coordinates stay normal doubles); an algorithm other than a1, a2,
// a3; density outside (1, 2] for a1 and a2; a generator version this build
// does not have.
Status ValidateWorld(const World& world);

// The world with fields that do not affect its points normalised (density for
// A3), so equal worlds compare and hash equal.
World CanonicalWorld(World world);

// A 64-bit digest of a canonical world, for seeds and cache keys.
uint64_t WorldFingerprint(const World& world);

// "seed=7 d=1 algorithm=a3 density=2 version=1", for logs and errors.
std::string DescribeWorld(const World& world);

}  // namespace scallop
