// RadiusField: the spacing R(x) > 0 a world wants at x (issue 24), as plain parameters
// (RadiusFieldSpec) and as a validated value (RadiusField) with bit-deterministic evaluation,
// interval bounds, a Lipschitz bound, raster masks and a fingerprint. See docs/design.md.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

#include "scallop/base/status.h"
#include "scallop/field/value_noise.h"
#include "scallop/geometry/rect.h"
#include "scallop/geometry/vec2.h"

namespace scallop {

enum class RadiusFieldKind { kConstant, kNoise, kRaster };

// "constant", "noise", "raster".
std::string_view RadiusFieldKindName(RadiusFieldKind kind);

// A grayscale image, rows bottom-up: pixels[j * width + i] is column i of row j, and row 0 is
// the image's bottom row (the lowest y in the world), the last row of the PNG file.
struct RasterImage {
  int width = 0;
  int height = 0;
  int bit_depth = 8;  // 8 or 16; v_max = 2^bit_depth - 1
  std::vector<uint16_t> pixels;
};

// Limits a field must keep (each is checked by ValidateRadiusFieldSpec).
// r_max / r_min: the sampler's grids and the verifier's cells scale with it; 100 is the issue's
// aim and costs memory only where the field is small.
inline constexpr double kMaxRadiusRatio = 100.0;
// The field's Lipschitz bound L (|R(x) - R(y)| <= L |x - y|). Below 1 the spots at the spacing
// around a point form one star-shaped curve (docs/design.md, "Radius fields"); 1/2 keeps that
// curve's slope and the search windows (R / (1 - L)) within a factor 2 of the radius.
inline constexpr double kMaxFieldSlope = 0.5;
// Raster size: each side at most 16384 pixels and at most 2^24 pixels in all (32 MiB of
// 16-bit pixels plus a 64 MiB mask table).
inline constexpr int kMaxRasterSide = 16384;
inline constexpr int64_t kMaxRasterPixels = int64_t{1} << 24;
// Radii the core supports, as for the constant spacing (sampling/sampler.h).
inline constexpr double kSmallestFieldRadius = 0x1.0p-256;
inline constexpr double kLargestFieldRadius = 0x1.0p256;

// Plain parameters, as a caller sends them; nothing is checked here.
struct RadiusFieldSpec {
  RadiusFieldKind kind = RadiusFieldKind::kConstant;
  // constant: R = r_min and r_max must equal it. noise and raster: the range R maps onto.
  double r_min = 1.0;
  double r_max = 1.0;
  // noise: fractal value noise with its own seed; octave k has frequency * 2^k (cycles per
  // unit of world length) and weight gain^k.
  uint64_t noise_seed = 0;
  double frequency = 0.01;
  int octaves = 3;
  double gain = 0.5;
  // raster: the image, the world position of its lower-left corner and the side of a pixel.
  std::shared_ptr<const RasterImage> raster = nullptr;
  Vec2 raster_origin = {};
  double pixel_size = 1.0;
};

// Checks every parameter and returns INVALID_ARGUMENT naming the first bad one and its allowed
// range: field.r_min (finite, in [2^-256, 2^256]), field.r_max (>= r_min, = r_min for constant,
// r_max / r_min <= 100), field.frequency, field.octaves (1..8), field.gain ((0, 1]),
// raster (present, 8 or 16 bit, sides 1..16384, at most 2^24 pixels, pixel count matching),
// raster.pixel_size, raster.origin (finite), and the slope: "field.frequency" (noise) or
// "raster.pixel_size" (raster) when the field's Lipschitz bound exceeds kMaxFieldSlope.
// Cost: O(1), a raster O(pixels).
Status ValidateRadiusFieldSpec(const RadiusFieldSpec& spec);

struct RadiusInterval {
  double lo = 0.0;
  double hi = 0.0;
};

// A validated field. Immutable and cheap to copy (a raster's pixels are shared); safe to share
// between threads. Every query is a pure function of the spec's bits.
class RadiusField {
 public:
  // Validates, then builds (a raster: O(pixels) for the mask table).
  static StatusOr<RadiusField> Create(const RadiusFieldSpec& spec);
  // REQUIRES: r in [kSmallestFieldRadius, kLargestFieldRadius].
  static RadiusField Constant(double r);

  const RadiusFieldSpec& spec() const { return spec_; }
  RadiusFieldKind kind() const { return spec_.kind; }
  double r_min() const { return spec_.r_min; }
  double r_max() const { return spec_.r_max; }

  // R(x) in [r_min, r_max]. Bit-deterministic: only IEEE + - * /, floor and integer hashing,
  // in a written order (no libm transcendental, no FMA: the build uses -ffp-contract=off).
  // Raster: each pixel's value sits at its centre, bilinear between centres, the edge pixels'
  // values beyond the image; a masked pixel (v = 0) counts as v_max. Cost: constant O(1);
  // noise 4 mixes per octave; raster 4 pixel reads. Defined for every input: infinities and
  // NaN give some value in [r_min, r_max] (never undefined behaviour).
  double Evaluate(Vec2 x) const;

  // A noise field's R for fractal noise n in [0, 1]: r_min + (r_max - r_min) n, the last step of
  // Evaluate (FieldEvaluator ends with it too). O(1).
  double NoiseRadius(double n) const { return spec_.r_min + (spec_.r_max - spec_.r_min) * n; }

  // L with |R(x) - R(y)| <= L |x - y| for all x, y (0 for a constant): noise from the fade's
  // slope (value_noise.h), raster from the largest step between neighbouring pixels over the
  // pixel size. Rounding of Evaluate may exceed it by ~1e-15 r_max, which Bounds absorbs.
  double Slope() const { return slope_; }

  // Bounds of R over the closed rectangle: R(centre) -+ (L * half diagonal + 1e-12 r_max),
  // clipped to [r_min, r_max]. Conservative (certificates rely on it). O(one Evaluate).
  RadiusInterval Bounds(const Rect& r) const;
  // The same bounds given R at the rectangle's centre (from Evaluate or FieldEvaluator), so that
  // a caller with a faster evaluator gets the same bits. O(1).
  RadiusInterval BoundsAround(const Rect& r, double centre_radius) const;

  // The hashed seed of each noise octave (OctaveSeed(noise_seed, k)), computed once here so that
  // an evaluation hashes only its lattice corners. Zero for the other kinds.
  const std::array<uint64_t, kMaxNoiseOctaves>& octave_seeds() const { return octave_seeds_; }

  // True when x lies in a masked pixel's half-open square (raster only). O(1).
  bool IsMasked(Vec2 x) const;
  bool HasMask() const { return mask_count_ != nullptr; }
  // Judged on the rectangle's inside (x0, x1) x (y0, y1), whose pixels are columns
  // floor(u0)..ceil(u1) - 1 in pixel units: its edges belong to the neighbouring cells, which
  // judge them. AnyMasked: some masked pixel meets the inside. AllMasked: every spot of the
  // inside is in a masked pixel. O(1) (summed-area table).
  bool AnyMasked(const Rect& r) const;
  bool AllMasked(const Rect& r) const;

  // Cuts a partly masked rectangle along the raster's pixel lines nearest its centre that cross
  // its inside (one vertical, one horizontal, or both) so that repeated cutting ends in pieces
  // that are wholly masked or wholly unmasked. Writes 2 or 4 pieces and returns their number,
  // or 0 when no pixel line crosses it. O(1).
  int CutAtPixelLines(const Rect& r, Rect pieces[4]) const;

  // A 64-bit hash of the kind and every parameter's bits; a raster's pixels enter by a fold
  // h = Mix64(h + word) over the pixels packed four to a 64-bit word (rows bottom-up).
  uint64_t Fingerprint() const { return fingerprint_; }

 private:
  RadiusFieldSpec spec_;
  double slope_ = 0.0;
  uint64_t fingerprint_ = 0;
  std::array<uint64_t, kMaxNoiseOctaves> octave_seeds_ = {};
  // Raster: radius of each pixel value (v = 0 maps to r_max), and the summed-area table of
  // masked pixels ((width + 1) * (height + 1) counts), null when nothing is masked.
  std::shared_ptr<const std::vector<double>> value_radius_;
  std::shared_ptr<const std::vector<uint32_t>> mask_count_;

  double EvaluateRaster(Vec2 x) const;
  // Masked pixels meeting the rectangle's inside, and how many pixels that is (-1 when part of
  // the rectangle lies beyond the image).
  int64_t MaskedIn(const Rect& r, int64_t* pixels_in_range) const;
};

}  // namespace scallop
