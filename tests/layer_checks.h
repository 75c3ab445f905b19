// The forest, and brute-force oracles for layered points (issue 19), written from the
// definitions and apart from the code under test: every pair under the exclusion matrix, and each
// layer's largest slack given all the points, probed on a jittered lattice. For the plane's layered
// worlds and the bounded layered sampler alike.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "scallop/geometry/rect.h"
#include "scallop/plane/plane_engine.h"
#include "scallop/plane/world_layers.h"
#include "scallop/random/rng.h"
#include "scallop/sampling/layered_sampler.h"
#include "tests/field_test_fields.h"
#include "tests/test_worlds.h"

namespace scallop {

// Trees, bushes and rocks at the radii, the default matrix; with `field_bushes`, the
// bushes' spacing is noise from 2 to 4, and rocks keep 2.5 from trees.
inline World Forest(uint64_t seed, bool field_bushes = false) {
  WorldSpec spec{.seed = seed};
  spec.layers = {{.name = "trees", .min_distance = 8},
                 {.name = "bushes", .min_distance = 3},
                 {.name = "rocks", .min_distance = 1.5}};
  if (field_bushes) {
    spec.layers[1].radius_field = field_test::NoiseField(seed, 2.0, 2.0).spec();
    spec.exclusions = {{.first = "rocks", .second = "trees", .distance = 2.5}};
  }
  return ValidWorld(spec);
}

// A bounded run's points in the form the checks below read (no ids).
inline PlanePoints AsPlanePoints(const LayeredPoints& sampled) {
  PlanePoints points;
  points.positions = sampled.positions;
  points.layers = sampled.layers;
  return points;
}

// The rule between two points of layers a and b: a layer's own spacing (max of R at both for a
// field), D between layers. Written from the definition, not from the verifier.
inline double Rule(const WorldLayers& layers, int a, Vec2 p, int b, Vec2 q) {
  if (a != b) return layers.exclusion(a, b);
  const World& w = layers.world(a);
  return std::max(w.SpacingAt(p), w.SpacingAt(q));
}

// Pairs of the set with an end in the window closer than their rule (dx^2 + dy^2 < m^2), by
// looking at every pair.
inline int64_t BruteForceConflicts(const PlanePoints& points, const WorldLayers& layers,
                                   const Rect& window, double* worst_ratio = nullptr) {
  int64_t conflicts = 0;
  double worst = INFINITY;
  const size_t n = points.positions.size();
  for (size_t a = 0; a < n; ++a) {
    for (size_t b = a + 1; b < n; ++b) {
      const Vec2 p = points.positions[a], q = points.positions[b];
      if (!window.Contains(p) && !window.Contains(q)) continue;
      const double m = Rule(layers, points.layers[a], p, points.layers[b], q);
      const double dx = p.x - q.x, dy = p.y - q.y;
      if (dx * dx + dy * dy < m * m) ++conflicts;
      if (m > 0) worst = std::min(worst, std::sqrt(dx * dx + dy * dy) / m);
    }
  }
  if (worst_ratio != nullptr) *worst_ratio = worst;
  return conflicts;
}

// The largest slack over probes of the window, for layer k: min over the layer's points q of
// |x - q| - max(R(x), R(q)) and over other layers' points c of |x - c| - D; negative means the
// spot is covered or excluded. Probes on a jittered lattice `step` apart.
struct Probe {
  double worst = -INFINITY;
  Vec2 spot;
  int64_t probes = 0;
};
inline Probe BruteForceGap(const PlanePoints& points, const WorldLayers& layers, int k,
                           const Rect& window, double step, uint64_t seed) {
  Probe result;
  Rng rng(seed);
  const World& own = layers.world(k);
  for (double y = window.y0; y <= window.y1; y += step) {
    for (double x = window.x0; x <= window.x1; x += step) {
      const Vec2 s{std::min(window.x1, x + rng.Uniform(0, 0.5 * step)),
                   std::min(window.y1, y + rng.Uniform(0, 0.5 * step))};
      // A masked spot needs no point of the layer.
      if (own.radius_field() != nullptr && own.radius_field()->IsMasked(s)) continue;
      const double rs = own.SpacingAt(s);
      double slack = INFINITY;
      for (size_t m = 0; m < points.positions.size(); ++m) {
        const Vec2 q = points.positions[m];
        const double d = std::sqrt(SquaredDistance(s, q));
        const int layer = points.layers[m];
        slack = std::min(slack, layer == k ? d - std::max(rs, own.SpacingAt(q))
                                           : d - layers.exclusion(layer, k));
      }
      ++result.probes;
      if (slack > result.worst) {
        result.worst = slack;
        result.spot = s;
      }
    }
  }
  return result;
}

}  // namespace scallop
