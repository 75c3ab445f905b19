// Worlds for tests: a WorldSpec made a World, failing the test at once if the
// spec is not valid (a test's own mistake, never the code under test's).
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>

#include "scallop/plane/world.h"
#include "scallop/random/rng.h"

namespace scallop {

inline World ValidWorld(const WorldSpec& spec) {
  StatusOr<World> world = World::Create(spec);
  if (!world.ok()) {
    ADD_FAILURE() << "test world is invalid: " << world.status().message();
    std::abort();
  }
  return *world;
}

// A world of `algorithm` and d with a seed, and for A1 and A2 a density in
// [1.05, 2), drawn from `dice` in that order (so a printed dice seed replays it).
inline World DiceWorld(Rng& dice, WorldAlgorithm algorithm, double d) {
  WorldSpec spec{.seed = dice.NextBits(), .min_distance = d, .algorithm = algorithm};
  if (UsesDensity(algorithm)) spec.density = dice.Uniform(1.05, 2.0);
  return ValidWorld(spec);
}

}  // namespace scallop
