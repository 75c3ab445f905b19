// Random radius fields for tests (noise, raster, masked raster, constant) within the slope
// bound, and brute-force oracles for the max rule written apart from the code under test:
// every pair, and dense probing with R at the probe.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <span>
#include <vector>

#include "scallop/field/radius_field.h"
#include "scallop/field/value_noise.h"
#include "scallop/plane/world.h"
#include "scallop/random/rng.h"
#include "tests/test_worlds.h"

namespace scallop::field_test {

enum class FieldCase { kConstant, kNoise, kRaster, kMaskedRaster };

inline const char* CaseName(FieldCase c) {
  switch (c) {
    case FieldCase::kConstant:
      return "constant";
    case FieldCase::kNoise:
      return "noise";
    case FieldCase::kRaster:
      return "raster";
    case FieldCase::kMaskedRaster:
      return "masked-raster";
  }
  return "?";
}

// A noise field over [r_min, ratio r_min] at 90% of the slope bound.
inline RadiusField NoiseField(uint64_t seed, double r_min, double ratio, int octaves = 3) {
  RadiusFieldSpec spec;
  spec.kind = RadiusFieldKind::kNoise;
  spec.r_min = r_min;
  spec.r_max = r_min * ratio;
  spec.noise_seed = seed;
  spec.octaves = octaves;
  spec.gain = 0.5;
  spec.frequency = 0.9 * kMaxFieldSlope /
                   ((spec.r_max - spec.r_min) * FractalValueNoiseSlope(1.0, octaves, 0.5));
  return *RadiusField::Create(spec);
}

// A w x h 8-bit raster from smooth noise placed over `area`; with `masked`, blobs where the
// noise is lowest become v = 0. The pixel size grows until the slope bound holds.
inline RadiusField RasterField(uint64_t seed, double r_min, double ratio, int w, int h, double x0,
                               double y0, double side, bool masked) {
  auto image = std::make_shared<RasterImage>();
  image->width = w;
  image->height = h;
  image->bit_depth = 8;
  Rng rng(seed);
  const double phase = rng.Uniform(0.0, 100.0);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const double n = FractalValueNoise(seed, 0.25, 2, 0.5, i + phase, j);
      auto v = static_cast<uint16_t>(1 + std::lround(n * 254.0));
      if (masked && n < 0.3) v = 0;
      image->pixels.push_back(v);
    }
  }
  RadiusFieldSpec spec;
  spec.kind = RadiusFieldKind::kRaster;
  spec.r_min = r_min;
  spec.r_max = r_min * ratio;
  spec.raster = image;
  spec.raster_origin = {x0, y0};
  spec.pixel_size = side / std::max(w, h);
  for (;;) {
    StatusOr<RadiusField> field = RadiusField::Create(spec);
    if (field.ok()) return *field;
    spec.pixel_size *= 1.25;
  }
}

inline RadiusField MakeField(FieldCase c, uint64_t seed, double r_min, double ratio,
                             const Rect& domain) {
  switch (c) {
    case FieldCase::kConstant:
      return RadiusField::Constant(r_min);
    case FieldCase::kNoise:
      return NoiseField(seed, r_min, ratio);
    case FieldCase::kRaster:
      return RasterField(seed, r_min, ratio, 12, 9, domain.x0, domain.y0, domain.Width(), false);
    case FieldCase::kMaskedRaster:
      return RasterField(seed, r_min, ratio, 12, 9, domain.x0, domain.y0, domain.Width(), true);
  }
  return RadiusField::Constant(r_min);
}

// A field world on the plane (a3) with r_min `r_min`: noise over the whole plane, or a 20 x 20
// raster whose image covers [-10 r_max, 10 r_max)^2 or more (the pixel size grows until the
// slope bound holds), a few regions of 6 r_max a side, with masked blobs for the masked case.
inline World PlaneWorld(FieldCase c, uint64_t seed, double r_min, double ratio) {
  const double extent = 10.0 * ratio * r_min;
  const RadiusField field = c == FieldCase::kNoise
                                ? NoiseField(seed, r_min, ratio)
                                : RasterField(seed, r_min, ratio, 20, 20, -extent, -extent,
                                              2 * extent, c == FieldCase::kMaskedRaster);
  WorldSpec spec{.seed = seed, .algorithm = WorldAlgorithm::kA3};
  spec.radius_field = field.spec();
  return ValidWorld(spec);
}

// Pairs with |p - q|^2 < max(R(p), R(q))^2, by looking at every pair.
inline int64_t BruteForceConflicts(std::span<const Vec2> points, const RadiusField& field) {
  int64_t conflicts = 0;
  for (size_t a = 0; a < points.size(); ++a) {
    for (size_t b = a + 1; b < points.size(); ++b) {
      const double m = std::max(field.Evaluate(points[a]), field.Evaluate(points[b]));
      const double dx = points[a].x - points[b].x;
      const double dy = points[a].y - points[b].y;
      if (dx * dx + dy * dy < m * m) ++conflicts;
    }
  }
  return conflicts;
}

struct ProbeResult {
  double worst_gap = -std::numeric_limits<double>::infinity();  // max over probes of G
  Vec2 worst_spot;
  int64_t probes = 0;
};

// G(x) = min_q |x - q| - max(R(x), R(q)) at a lattice of unmasked probes of step `step`
// (offset by a seeded jitter) over the closed domain, against every point.
inline ProbeResult BruteForceProbe(std::span<const Vec2> points, const RadiusField& field,
                                   const Rect& domain, double step, uint64_t seed) {
  ProbeResult result;
  std::vector<double> radius;
  for (const Vec2& q : points) radius.push_back(field.Evaluate(q));
  Rng rng(seed);
  const double ox = rng.Uniform(0.0, step);
  const double oy = rng.Uniform(0.0, step);
  for (double y = domain.y0 + oy; y <= domain.y1; y += step) {
    for (double x = domain.x0 + ox; x <= domain.x1; x += step) {
      const Vec2 probe{x, y};
      if (field.IsMasked(probe)) continue;
      ++result.probes;
      const double rx = field.Evaluate(probe);
      double g = std::numeric_limits<double>::infinity();
      for (size_t k = 0; k < points.size(); ++k) {
        const Vec2 q = points[k];
        g = std::min(g, std::hypot(x - q.x, y - q.y) - std::max(rx, radius[k]));
      }
      if (g > result.worst_gap) {
        result.worst_gap = g;
        result.worst_spot = probe;
      }
    }
  }
  return result;
}

}  // namespace scallop::field_test
