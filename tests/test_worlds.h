// Worlds for tests: a WorldSpec made a World, failing the test at once if the
// spec is not valid (a test's own mistake, never the code under test's).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <vector>

#include "scallop/geometry/rect.h"
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

// The tiles of the grid whose column and row edges are xs and ys (sorted here), in an order
// shuffled by `rng`: for tests that ask for a rectangle piece by piece in a random order.
inline std::vector<Rect> ShuffledTiles(std::vector<double> xs, std::vector<double> ys, Rng& rng) {
  std::sort(xs.begin(), xs.end());
  std::sort(ys.begin(), ys.end());
  std::vector<Rect> tiles;
  for (size_t j = 0; j + 1 < ys.size(); ++j) {
    for (size_t i = 0; i + 1 < xs.size(); ++i)
      tiles.push_back({xs[i], ys[j], xs[i + 1], ys[j + 1]});
  }
  for (size_t k = tiles.size(); k > 1; --k) std::swap(tiles[k - 1], tiles[rng.Below(k)]);
  return tiles;
}

}  // namespace scallop
