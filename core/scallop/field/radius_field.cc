// RadiusField: validation of the plain parameters, then evaluation, bounds, masks and the
// fingerprint of a valid field. The arithmetic order here is part of every field world's bits.
#include "scallop/field/radius_field.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "scallop/field/value_noise.h"
#include "scallop/random/rng.h"

namespace scallop {
namespace {

std::string Num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

Status Bad(const char* field, const std::string& what) {
  std::string message(field);
  message.append(1, ' ').append(what);
  return InvalidArgument(std::move(message));
}

// Largest |R difference| between horizontally and vertically neighbouring pixels.
void LargestPixelSteps(const RasterImage& image, const std::vector<double>& radius, double* dx,
                       double* dy) {
  double sx = 0.0;
  double sy = 0.0;
  const int w = image.width;
  for (int j = 0; j < image.height; ++j) {
    for (int i = 0; i < w; ++i) {
      const double r = radius[image.pixels[static_cast<size_t>(j) * w + i]];
      if (i + 1 < w) {
        sx = std::max(sx, std::abs(radius[image.pixels[static_cast<size_t>(j) * w + i + 1]] - r));
      }
      if (j + 1 < image.height) {
        sy = std::max(sy, std::abs(radius[image.pixels[static_cast<size_t>(j + 1) * w + i]] - r));
      }
    }
  }
  *dx = sx;
  *dy = sy;
}

std::vector<double> ValueRadii(const RadiusFieldSpec& spec) {
  const int v_max = spec.raster->bit_depth == 16 ? 65535 : 255;
  std::vector<double> radius(static_cast<size_t>(v_max) + 1);
  const double span = spec.r_max - spec.r_min;
  radius[0] = spec.r_max;  // a masked pixel counts as v_max in the blend
  for (int v = 1; v <= v_max; ++v) {
    radius[v] = spec.r_min + span * static_cast<double>(v - 1) / static_cast<double>(v_max - 1);
  }
  radius[v_max] = spec.r_max;  // exact at the top, whatever the division rounded to
  return radius;
}

double RasterSlope(const RadiusFieldSpec& spec, const std::vector<double>& radius) {
  double dx = 0.0;
  double dy = 0.0;
  LargestPixelSteps(*spec.raster, radius, &dx, &dy);
  // Inside a bilinear cell dR/dx is a convex combination of two horizontal steps over the
  // pixel size, dR/dy of two vertical ones.
  return std::sqrt(dx * dx + dy * dy) / spec.pixel_size * (1.0 + 1e-12);
}

double NoiseSlope(const RadiusFieldSpec& spec) {
  return (spec.r_max - spec.r_min) *
         FractalValueNoiseSlope(spec.frequency, spec.octaves, spec.gain);
}

}  // namespace

std::string_view RadiusFieldKindName(RadiusFieldKind kind) {
  switch (kind) {
    case RadiusFieldKind::kConstant:
      return "constant";
    case RadiusFieldKind::kNoise:
      return "noise";
    case RadiusFieldKind::kRaster:
      return "raster";
  }
  return "unknown";
}

Status ValidateRadiusFieldSpec(const RadiusFieldSpec& spec) {
  const std::string range = "[2^-256, 2^256]";
  if (!std::isfinite(spec.r_min) || spec.r_min < kSmallestFieldRadius ||
      spec.r_min > kLargestFieldRadius) {
    return Bad("field.r_min", "must be finite and in " + range + ", got " + Num(spec.r_min));
  }
  if (!std::isfinite(spec.r_max) || spec.r_max < spec.r_min || spec.r_max > kLargestFieldRadius) {
    return Bad("field.r_max",
               "must be finite, >= field.r_min and <= 2^256, got " + Num(spec.r_max));
  }
  if (spec.kind == RadiusFieldKind::kConstant && spec.r_max != spec.r_min) {
    return Bad("field.r_max", "must equal field.r_min for a constant field, got " +
                                  Num(spec.r_max) + " and " + Num(spec.r_min));
  }
  if (spec.r_max / spec.r_min > kMaxRadiusRatio) {
    return Bad("field.r_max", "/ field.r_min must be at most " + Num(kMaxRadiusRatio) + ", got " +
                                  Num(spec.r_max / spec.r_min));
  }
  if (spec.kind == RadiusFieldKind::kNoise) {
    if (!std::isfinite(spec.frequency) || spec.frequency <= 0.0) {
      return Bad("field.frequency", "must be finite and > 0, got " + Num(spec.frequency));
    }
    if (spec.octaves < 1 || spec.octaves > kMaxNoiseOctaves) {
      return Bad("field.octaves", "must be in [1, 8], got " + std::to_string(spec.octaves));
    }
    if (!std::isfinite(spec.gain) || spec.gain <= 0.0 || spec.gain > 1.0) {
      return Bad("field.gain", "must be in (0, 1], got " + Num(spec.gain));
    }
    const double slope = NoiseSlope(spec);
    if (!(slope <= kMaxFieldSlope)) {
      return Bad("field.frequency",
                 "too high for the radius range: the noise field's slope bound (r_max - r_min) * "
                 "frequency * (15/8) sqrt(2) * octave factor is " +
                     Num(slope) + ", must be at most " + Num(kMaxFieldSlope) +
                     "; lower field.frequency, field.octaves or field.gain, or narrow the range");
    }
  }
  if (spec.kind == RadiusFieldKind::kRaster) {
    if (spec.raster == nullptr) return Bad("raster", "is missing");
    const RasterImage& image = *spec.raster;
    if (image.bit_depth != 8 && image.bit_depth != 16) {
      return Bad("raster.bit_depth",
                 "must be 8 or 16 (grayscale), got " + std::to_string(image.bit_depth));
    }
    if (image.width < 1 || image.height < 1 || image.width > kMaxRasterSide ||
        image.height > kMaxRasterSide || int64_t{image.width} * image.height > kMaxRasterPixels) {
      return Bad("raster", "size must be 1..16384 pixels a side and at most 2^24 pixels, got " +
                               std::to_string(image.width) + " x " + std::to_string(image.height));
    }
    if (image.pixels.size() != static_cast<size_t>(image.width) * image.height) {
      return Bad("raster.pixels",
                 "count must be width * height, got " + std::to_string(image.pixels.size()));
    }
    if (image.bit_depth == 8) {
      for (uint16_t v : image.pixels) {
        if (v > 255) return Bad("raster.pixels", "exceed 255 in an 8-bit raster");
      }
    }
    if (!std::isfinite(spec.pixel_size) || spec.pixel_size <= 0.0) {
      return Bad("raster.pixel_size", "must be finite and > 0, got " + Num(spec.pixel_size));
    }
    if (!std::isfinite(spec.raster_origin.x) || !std::isfinite(spec.raster_origin.y)) {
      return Bad("raster.origin", "must be finite");
    }
    const std::vector<double> radius = ValueRadii(spec);
    const double slope = RasterSlope(spec, radius);
    if (!(slope <= kMaxFieldSlope)) {
      return Bad("raster.pixel_size",
                 "too small for the image's steps: the raster field's slope bound (largest "
                 "radius step between neighbouring pixels / pixel size) is " +
                     Num(slope) + ", must be at most " + Num(kMaxFieldSlope) +
                     "; enlarge raster.pixel_size, smooth the image or narrow the range");
    }
  }
  return Status::Ok();
}

StatusOr<RadiusField> RadiusField::Create(const RadiusFieldSpec& spec) {
  if (Status s = ValidateRadiusFieldSpec(spec); !s.ok()) return s;
  RadiusField field;
  field.spec_ = spec;
  uint64_t h =
      HashWords({0x5241444955534649ULL, static_cast<uint64_t>(spec.kind),
                 std::bit_cast<uint64_t>(spec.r_min), std::bit_cast<uint64_t>(spec.r_max)});
  switch (spec.kind) {
    case RadiusFieldKind::kConstant:
      field.spec_.raster = nullptr;
      break;
    case RadiusFieldKind::kNoise:
      field.slope_ = NoiseSlope(spec);
      for (int k = 0; k < spec.octaves; ++k)
        field.octave_seeds_[k] = OctaveSeed(spec.noise_seed, k);
      h = HashWords({h, spec.noise_seed, std::bit_cast<uint64_t>(spec.frequency),
                     static_cast<uint64_t>(spec.octaves), std::bit_cast<uint64_t>(spec.gain)});
      field.spec_.raster = nullptr;
      break;
    case RadiusFieldKind::kRaster: {
      auto radius = std::make_shared<std::vector<double>>(ValueRadii(spec));
      field.slope_ = RasterSlope(spec, *radius);
      field.value_radius_ = radius;
      const RasterImage& image = *spec.raster;
      h = HashWords({h, static_cast<uint64_t>(image.width), static_cast<uint64_t>(image.height),
                     static_cast<uint64_t>(image.bit_depth),
                     std::bit_cast<uint64_t>(spec.raster_origin.x),
                     std::bit_cast<uint64_t>(spec.raster_origin.y),
                     std::bit_cast<uint64_t>(spec.pixel_size)});
      const size_t n = image.pixels.size();
      for (size_t k = 0; k < n; k += 4) {
        uint64_t word = 0;
        for (size_t m = 0; m < 4 && k + m < n; ++m) {
          word |= static_cast<uint64_t>(image.pixels[k + m]) << (16 * m);
        }
        h = Mix64(h + word);
      }
      const bool any_masked =
          std::find(image.pixels.begin(), image.pixels.end(), 0) != image.pixels.end();
      if (any_masked) {
        const int w = image.width;
        auto count = std::make_shared<std::vector<uint32_t>>(
            static_cast<size_t>(w + 1) * (image.height + 1), 0u);
        for (int j = 0; j < image.height; ++j) {
          for (int i = 0; i < w; ++i) {
            const uint32_t m = image.pixels[static_cast<size_t>(j) * w + i] == 0 ? 1u : 0u;
            (*count)[static_cast<size_t>(j + 1) * (w + 1) + i + 1] =
                m + (*count)[static_cast<size_t>(j) * (w + 1) + i + 1] +
                (*count)[static_cast<size_t>(j + 1) * (w + 1) + i] -
                (*count)[static_cast<size_t>(j) * (w + 1) + i];
          }
        }
        field.mask_count_ = count;
      }
      break;
    }
  }
  field.fingerprint_ = h;
  return field;
}

RadiusField RadiusField::Constant(double r) {
  RadiusFieldSpec spec;
  spec.r_min = r;
  spec.r_max = r;
  return *Create(spec);
}

double RadiusField::Evaluate(Vec2 x) const {
  switch (spec_.kind) {
    case RadiusFieldKind::kConstant:
      return spec_.r_min;
    case RadiusFieldKind::kNoise: {
      // FractalValueNoise with the octave seeds hashed once, at Create: the same bits.
      const double n = FractalSum(
          spec_.frequency, spec_.octaves, spec_.gain, x.x, x.y,
          [&](int k, double xs, double ys) { return ValueNoiseOctave(octave_seeds_[k], xs, ys); });
      return NoiseRadius(n);
    }
    case RadiusFieldKind::kRaster:
      return EvaluateRaster(x);
  }
  return spec_.r_max;
}

double RadiusField::EvaluateRaster(Vec2 x) const {
  const RasterImage& image = *spec_.raster;
  const std::vector<double>& radius = *value_radius_;
  const int w = image.width;
  const int h = image.height;
  // Pixel-centre coordinates: centre of pixel i at u = i. Clamped before the integer
  // conversion so that far coordinates cannot overflow; beyond the image the edge holds.
  double u = (x.x - spec_.raster_origin.x) / spec_.pixel_size - 0.5;
  double v = (x.y - spec_.raster_origin.y) / spec_.pixel_size - 0.5;
  // Written so that NaN lands on 0 too: no input reaches the integer conversion out of range.
  u = u > 0.0 ? std::min(u, static_cast<double>(w - 1)) : 0.0;
  v = v > 0.0 ? std::min(v, static_cast<double>(h - 1)) : 0.0;
  const double fu = std::floor(u);
  const double fv = std::floor(v);
  const int i0 = static_cast<int>(fu);
  const int j0 = static_cast<int>(fv);
  const int i1 = std::min(i0 + 1, w - 1);
  const int j1 = std::min(j0 + 1, h - 1);
  const double a = u - fu;
  const double b = v - fv;
  const auto at = [&](int i, int j) {
    return radius[image.pixels[static_cast<size_t>(j) * w + i]];
  };
  const double bottom = at(i0, j0) + (at(i1, j0) - at(i0, j0)) * a;
  const double top = at(i0, j1) + (at(i1, j1) - at(i0, j1)) * a;
  const double r = bottom + (top - bottom) * b;
  return std::clamp(r, spec_.r_min, spec_.r_max);
}

RadiusInterval RadiusField::Bounds(const Rect& r) const {
  if (spec_.kind == RadiusFieldKind::kConstant) return {spec_.r_min, spec_.r_max};
  return BoundsAround(r, Evaluate({0.5 * (r.x0 + r.x1), 0.5 * (r.y0 + r.y1)}));
}

RadiusInterval RadiusField::BoundsAround(const Rect& r, double centre_radius) const {
  if (spec_.kind == RadiusFieldKind::kConstant) return {spec_.r_min, spec_.r_max};
  const double half_diagonal = 0.5 * std::sqrt(r.Width() * r.Width() + r.Height() * r.Height());
  const double slack = slope_ * half_diagonal * (1.0 + 1e-12) + 1e-12 * spec_.r_max;
  return {std::max(spec_.r_min, centre_radius - slack),
          std::min(spec_.r_max, centre_radius + slack)};
}

bool RadiusField::IsMasked(Vec2 x) const {
  if (!HasMask()) return false;
  const RasterImage& image = *spec_.raster;
  const double u = (x.x - spec_.raster_origin.x) / spec_.pixel_size;
  const double v = (x.y - spec_.raster_origin.y) / spec_.pixel_size;
  if (!(u >= 0.0 && u < image.width && v >= 0.0 && v < image.height)) return false;
  const int i = static_cast<int>(u);
  const int j = static_cast<int>(v);
  return image.pixels[static_cast<size_t>(j) * image.width + i] == 0;
}

int64_t RadiusField::MaskedIn(const Rect& r, int64_t* pixels_in_range) const {
  *pixels_in_range = 0;
  if (!HasMask()) return 0;
  const RasterImage& image = *spec_.raster;
  const double w = image.width;
  const double h = image.height;
  const double u0 =
      std::clamp(std::floor((r.x0 - spec_.raster_origin.x) / spec_.pixel_size), -1.0, w);
  const double u1 =
      std::clamp(std::ceil((r.x1 - spec_.raster_origin.x) / spec_.pixel_size) - 1.0, -1.0, w);
  const double v0 =
      std::clamp(std::floor((r.y0 - spec_.raster_origin.y) / spec_.pixel_size), -1.0, h);
  const double v1 =
      std::clamp(std::ceil((r.y1 - spec_.raster_origin.y) / spec_.pixel_size) - 1.0, -1.0, h);
  const int i0 = static_cast<int>(std::max(u0, 0.0));
  const int i1 = static_cast<int>(std::min(u1, w - 1));
  const int j0 = static_cast<int>(std::max(v0, 0.0));
  const int j1 = static_cast<int>(std::min(v1, h - 1));
  if (i0 > i1 || j0 > j1) return 0;
  *pixels_in_range = (u0 >= 0.0 && u1 < w && v0 >= 0.0 && v1 < h)
                         ? int64_t{i1 - i0 + 1} * (j1 - j0 + 1)
                         : -1;  // part of the rectangle lies beyond the image: never all masked
  const std::vector<uint32_t>& c = *mask_count_;
  const size_t stride = static_cast<size_t>(image.width) + 1;
  return int64_t{c[(j1 + 1) * stride + i1 + 1]} - c[static_cast<size_t>(j0) * stride + i1 + 1] -
         c[(j1 + 1) * stride + i0] + c[static_cast<size_t>(j0) * stride + i0];
}

bool RadiusField::AnyMasked(const Rect& r) const {
  int64_t pixels = 0;
  return MaskedIn(r, &pixels) > 0;
}

bool RadiusField::AllMasked(const Rect& r) const {
  int64_t pixels = 0;
  const int64_t masked = MaskedIn(r, &pixels);
  return pixels > 0 && masked == pixels;
}

namespace {

// The pixel line (origin + k * size, k in [0, count]) nearest to the middle of (lo, hi) that
// lies strictly inside it, if any.
bool PixelLineInside(double lo, double hi, double origin, double size, int count, double* line) {
  const double k_lo = std::max(0.0, std::floor((lo - origin) / size) + 1.0);
  const double k_hi = std::min(static_cast<double>(count), std::ceil((hi - origin) / size) - 1.0);
  if (k_lo > k_hi) return false;
  const double k = std::clamp(std::round((0.5 * (lo + hi) - origin) / size), k_lo, k_hi);
  *line = origin + k * size;
  return lo < *line && *line < hi;
}

}  // namespace

int RadiusField::CutAtPixelLines(const Rect& r, Rect pieces[4]) const {
  if (spec_.kind != RadiusFieldKind::kRaster) return 0;
  const RasterImage& image = *spec_.raster;
  double x = 0.0;
  double y = 0.0;
  const bool cut_x =
      PixelLineInside(r.x0, r.x1, spec_.raster_origin.x, spec_.pixel_size, image.width, &x);
  const bool cut_y =
      PixelLineInside(r.y0, r.y1, spec_.raster_origin.y, spec_.pixel_size, image.height, &y);
  if (cut_x && cut_y) {
    pieces[0] = {r.x0, r.y0, x, y};
    pieces[1] = {x, r.y0, r.x1, y};
    pieces[2] = {r.x0, y, x, r.y1};
    pieces[3] = {x, y, r.x1, r.y1};
    return 4;
  }
  if (cut_x) {
    pieces[0] = {r.x0, r.y0, x, r.y1};
    pieces[1] = {x, r.y0, r.x1, r.y1};
    return 2;
  }
  if (cut_y) {
    pieces[0] = {r.x0, r.y0, r.x1, y};
    pieces[1] = {r.x0, y, r.x1, r.y1};
    return 2;
  }
  return 0;
}

}  // namespace scallop
