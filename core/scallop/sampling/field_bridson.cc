// SampleFieldBridson: the variable-radius Bridson sampler users have today, as the baseline the
// field sampler is measured against (same conflict rule, same grid, no certificate).
#include <cmath>

#include "scallop/random/rng.h"
#include "scallop/sampling/field_point_grid.h"
#include "scallop/sampling/field_sampler.h"

namespace scallop {

StatusOr<std::vector<Vec2>> SampleFieldBridson(const FieldSamplerOptions& options,
                                               const RadiusField& field, int attempts) {
  if (Status s = ValidateFieldSamplerOptions(options, field); !s.ok()) return s;
  if (attempts < 1) return InvalidArgument("attempts must be >= 1");
  const Rect& rect = options.domain;
  Rng rng(HashWords({options.seed, 0x42524944534f4eULL}));
  FieldPointGrid grid(rect, std::sqrt(field.r_min() * field.r_max()));
  const double reach_factor = (1.0 / (1.0 - field.Slope())) * (1.0 + 1e-9);
  std::vector<int32_t> active;
  const auto try_place = [&](Vec2 x) {
    if (!rect.Contains(x) || field.IsMasked(x)) return false;
    const double rx = field.Evaluate(x);
    if (grid.Conflicts(x, rx, std::min(field.r_max(), rx * reach_factor))) return false;
    active.push_back(static_cast<int32_t>(grid.points().size()));
    grid.Add(x, rx);
    return true;
  };
  for (int k = 0; k < 64; ++k) {
    if (try_place({rng.Uniform(rect.x0, rect.x1), rng.Uniform(rect.y0, rect.y1)})) break;
  }
  while (!active.empty()) {
    const size_t k = rng.Below(active.size());
    const FieldPoint p = grid.points()[static_cast<size_t>(active[k])];
    bool placed = false;
    for (int a = 0; a < attempts && !placed; ++a) {
      // Uniform by area in the annulus R(p)..2R(p).
      const double radius = p.r * std::sqrt(1.0 + 3.0 * rng.Uniform());
      const Vec2 u = UnitAt(6.283185307179586 * rng.Uniform());
      placed = try_place({p.p.x + radius * u.x, p.p.y + radius * u.y});
    }
    if (!placed) {
      active[k] = active.back();
      active.pop_back();
    }
  }
  std::vector<Vec2> out;
  out.reserve(grid.points().size());
  for (const FieldPoint& q : grid.points()) out.push_back(q.p);
  return out;
}

}  // namespace scallop
