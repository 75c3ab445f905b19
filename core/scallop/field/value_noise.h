// Seeded fractal value noise in [0, 1] whose bits are fixed: lattice values from a 64-bit hash,
// a quintic fade, only IEEE + - * / and floor (exact), so every machine gets the same numbers.
// Used by RadiusField's `noise` kind; its slope bound is what the field's Lipschitz bound uses.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "scallop/random/rng.h"

namespace scallop {

// Largest fractal octave count a noise field accepts.
inline constexpr int kMaxNoiseOctaves = 8;

// The seed of octave k: HashWords({seed, k}), computed once per octave.
inline uint64_t OctaveSeed(uint64_t seed, int octave) {
  return HashWords({seed, static_cast<uint64_t>(octave)});
}

// The value at lattice corner (i, j) of an octave: Mix64(octave_seed + i * A + j * B) (A, B
// the odd constants below, arithmetic mod 2^64), top 53 bits scaled to [0, 1). One mix per
// corner: the noise costs a quarter of what hashing the four words separately did.
inline double LatticeValue(uint64_t octave_seed, int64_t i, int64_t j) {
  const uint64_t h = Mix64(octave_seed + static_cast<uint64_t>(i) * 0x9e3779b97f4a7c15ULL +
                           static_cast<uint64_t>(j) * 0xd1b54a32d192ed03ULL);
  return static_cast<double>(h >> 11) * 0x1.0p-53;
}

// 6t^5 - 15t^4 + 10t^3: C2 at the lattice lines, derivative at most 15/8 (at t = 1/2).
inline double QuinticFade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

// Where (x, y), in lattice units, falls: its lattice cell (i, j) and the faded offsets inside.
struct LatticeSpot {
  int64_t i = 0;
  int64_t j = 0;
  double u = 0.0;  // QuinticFade(x - i)
  double v = 0.0;  // QuinticFade(y - j)
};

// floor(x) for |x| <= 2^62, without a call into libm (x86-64 has no floor instruction before
// SSE4.1): the truncation, less one when it rounded up. Exact, as floor is: beyond 2^52 every
// double is an integer and the conversion returns it unchanged. floor(-0.0) is -0.0 and this
// +0.0; the lattice index and the offset x - floor(x) (+0.0 either way) do not tell them apart.
inline double FloorWithin62Bits(double x) {
  const auto truncated = static_cast<double>(static_cast<int64_t>(x));
  return truncated > x ? truncated - 1.0 : truncated;
}

inline LatticeSpot LatticeSpotAt(double x, double y) {
  // Beyond 2^62 lattice units the integer conversion would overflow; the noise is flat there.
  // NaN goes to 0, so no input reaches the conversion out of range.
  x = x > -0x1.0p62 ? std::min(x, 0x1.0p62) : (x < 0.0 ? -0x1.0p62 : 0.0);
  y = y > -0x1.0p62 ? std::min(y, 0x1.0p62) : (y < 0.0 ? -0x1.0p62 : 0.0);
  const double fx = FloorWithin62Bits(x);
  const double fy = FloorWithin62Bits(y);
  return {static_cast<int64_t>(fx), static_cast<int64_t>(fy), QuinticFade(x - fx),
          QuinticFade(y - fy)};
}

// The lattice values at a cell's corners (i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1).
struct LatticeCorners {
  double a = 0.0;
  double b = 0.0;
  double c = 0.0;
  double d = 0.0;
};

inline LatticeCorners LatticeCornersOf(uint64_t octave_seed, int64_t i, int64_t j) {
  return {LatticeValue(octave_seed, i, j), LatticeValue(octave_seed, i + 1, j),
          LatticeValue(octave_seed, i, j + 1), LatticeValue(octave_seed, i + 1, j + 1)};
}

// The bilinear blend of the corners at the faded offsets.
inline double BlendCorners(const LatticeCorners& k, double u, double v) {
  const double bottom = k.a + (k.b - k.a) * u;
  const double top = k.c + (k.d - k.c) * u;
  return bottom + (top - bottom) * v;
}

// One octave of value noise at (x, y) in lattice units, in [0, 1). Each partial derivative is at
// most 15/8 (the fade's slope times a lattice difference below 1), so the gradient's norm is at
// most 15/8 * sqrt(2).
inline double ValueNoiseOctave(uint64_t octave_seed, double x, double y) {
  const LatticeSpot s = LatticeSpotAt(x, y);
  return BlendCorners(LatticeCornersOf(octave_seed, s.i, s.j), s.u, s.v);
}

// The fractal sum of octave(k, x * scale, y * scale) over `octaves` octaves, scale = frequency
// * 2^k, weight gain^k, divided by the sum of the weights and kept at most 1. This order of
// operations is part of every noise field's bits; FractalValueNoise and FieldEvaluator share it.
template <typename Octave>
inline double FractalSum(double frequency, int octaves, double gain, double x, double y,
                         Octave octave) {
  double sum = 0.0;
  double weight = 1.0;
  double total = 0.0;
  double scale = frequency;
  for (int k = 0; k < octaves; ++k) {
    sum += weight * octave(k, x * scale, y * scale);
    total += weight;
    weight *= gain;
    scale *= 2.0;
  }
  const double n = sum / total;
  return n < 1.0 ? n : 1.0;  // a rounding above 1 would leave [r_min, r_max]
}

// Fractal sum over `octaves` octaves, octave k at frequency * 2^k with weight gain^k, divided by
// the sum of the weights so the result stays in [0, 1]. REQUIRES: octaves in [1, 8], gain > 0.
// Cost: 4 mixes and ~20 flops per octave, plus the octave seeds' hashing.
inline double FractalValueNoise(uint64_t seed, double frequency, int octaves, double gain, double x,
                                double y) {
  return FractalSum(frequency, octaves, gain, x, y, [&](int k, double xs, double ys) {
    return ValueNoiseOctave(OctaveSeed(seed, k), xs, ys);
  });
}

// An upper bound of FractalValueNoise's gradient norm (per unit of x): sum_k gain^k 2^k f
// (15/8) sqrt(2) / sum_k gain^k, rounded up by a relative 1e-12.
inline double FractalValueNoiseSlope(double frequency, int octaves, double gain) {
  double sum = 0.0;
  double total = 0.0;
  double weight = 1.0;
  double scale = frequency;
  for (int k = 0; k < octaves; ++k) {
    sum += weight * scale;
    total += weight;
    weight *= gain;
    scale *= 2.0;
  }
  return sum / total * (15.0 / 8.0) * 1.4142135623730951 * (1.0 + 1e-12);
}

}  // namespace scallop
