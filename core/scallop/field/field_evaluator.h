// FieldEvaluator: R(x) for a run that evaluates many nearby spots, keeping each noise octave's
// last lattice cell (its four hashed corners) so that a spot in the same cell costs the fade
// and the blend only. The same bits as RadiusField::Evaluate, whatever the order of the spots.
#pragma once

#include <array>
#include <cstdint>

#include "scallop/field/radius_field.h"
#include "scallop/field/value_noise.h"
#include "scallop/geometry/rect.h"
#include "scallop/geometry/vec2.h"

namespace scallop {

// Holds a reference to the field, which must outlive it. Not thread-safe (the cache changes on
// every call): one evaluator per run or thread.
class FieldEvaluator {
 public:
  explicit FieldEvaluator(const RadiusField& field) : field_(field) {}

  // RadiusField::Evaluate(x), bit for bit. Noise: per octave, 4 mixes when x leaves the octave's
  // last lattice cell, none when it stays (at r_max / r_min = 8 and the slope bound, 3 in 4
  // evaluations of the field sampler stay in every octave's cell). Other kinds: Evaluate.
  double Evaluate(Vec2 x) {
    if (field_.kind() != RadiusFieldKind::kNoise) return field_.Evaluate(x);
    const RadiusFieldSpec& spec = field_.spec();
    const double n = FractalSum(
        spec.frequency, spec.octaves, spec.gain, x.x, x.y, [&](int k, double xs, double ys) {
          const LatticeSpot s = LatticeSpotAt(xs, ys);
          CachedCell& cell = cells_[static_cast<size_t>(k)];
          if (!cell.valid || cell.i != s.i || cell.j != s.j) {
            cell = {true, s.i, s.j,
                    LatticeCornersOf(field_.octave_seeds()[static_cast<size_t>(k)], s.i, s.j)};
          }
          return BlendCorners(cell.corners, s.u, s.v);
        });
    return field_.NoiseRadius(n);
  }

  // RadiusField::Bounds(r), bit for bit, with the centre evaluated here.
  RadiusInterval Bounds(const Rect& r) {
    if (field_.kind() == RadiusFieldKind::kConstant) return field_.Bounds(r);
    return field_.BoundsAround(r, Evaluate({0.5 * (r.x0 + r.x1), 0.5 * (r.y0 + r.y1)}));
  }

  const RadiusField& field() const { return field_; }

 private:
  struct CachedCell {
    bool valid = false;
    int64_t i = 0;
    int64_t j = 0;
    LatticeCorners corners;
  };

  const RadiusField& field_;
  std::array<CachedCell, kMaxNoiseOctaves> cells_ = {};
};

}  // namespace scallop
