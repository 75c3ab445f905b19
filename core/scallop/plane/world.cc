// World validation, normalisation and fingerprint.
#include "scallop/plane/world.h"

#include <bit>
#include <cmath>
#include <sstream>

#include "scallop/random/rng.h"

namespace scallop {

Status ValidateWorld(const World& world) {
  const double d = world.min_distance;
  if (!(d >= kSmallestMinDistance && d <= kLargestMinDistance)) {
    return InvalidArgument("world.min_distance: must be within [2^-256, 2^256], got " +
                           std::to_string(d));
  }
  if (world.algorithm != Algorithm::kA1 && world.algorithm != Algorithm::kA2 &&
      world.algorithm != Algorithm::kA3) {
    return InvalidArgument("world.algorithm: must be a1, a2 or a3, got " +
                           std::string(AlgorithmName(world.algorithm)));
  }
  if (UsesDensity(world.algorithm) &&
      (!std::isfinite(world.density) || world.density <= 1.0 || world.density > 2.0)) {
    return InvalidArgument("world.density: r'/2r must be in (1, 2] for a1 and a2, got " +
                           std::to_string(world.density));
  }
  if (world.generator_version != kGeneratorVersion) {
    return InvalidArgument("world.generator_version: this build generates version " +
                           std::to_string(kGeneratorVersion) + ", got " +
                           std::to_string(world.generator_version));
  }
  return Status::Ok();
}

World CanonicalWorld(World world) {
  if (!UsesDensity(world.algorithm)) world.density = 2.0;
  return world;
}

uint64_t WorldFingerprint(const World& world) {
  const World w = CanonicalWorld(world);
  return HashWords({w.seed, std::bit_cast<uint64_t>(w.min_distance),
                    static_cast<uint64_t>(w.algorithm), std::bit_cast<uint64_t>(w.density),
                    w.generator_version});
}

std::string DescribeWorld(const World& world) {
  std::ostringstream out;
  out << "seed=" << world.seed << " d=" << world.min_distance
      << " algorithm=" << AlgorithmName(world.algorithm);
  if (UsesDensity(world.algorithm)) out << " density=" << world.density;
  out << " version=" << world.generator_version;
  return out.str();
}

}  // namespace scallop
