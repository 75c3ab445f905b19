// VerifyLayeredWindow: the field verifier once per layer with the others as exclusion disks,
// and the pairs across layers through a grid.
#include "scallop/verify/layer_verifier.h"

#include <algorithm>
#include <cmath>

#include "scallop/sampling/field_point_grid.h"

namespace scallop {

StatusOr<LayerVerifyReport> VerifyLayeredWindow(std::span<const Vec2> points,
                                                std::span<const uint8_t> layer_of,
                                                const Rect& window,
                                                std::span<const RadiusField> fields,
                                                std::span<const double> matrix,
                                                const FieldVerifyOptions& options) {
  const size_t n = fields.size();
  if (points.size() != layer_of.size() || matrix.size() != n * n) {
    return InvalidArgument("layers: one layer a point and an n x n matrix for n layers");
  }
  for (const uint8_t layer : layer_of) {
    if (layer >= n) return InvalidArgument("layers: a point's layer is beyond the layers given");
  }
  double largest = 0.0;
  for (size_t a = 0; a < n; ++a) {
    for (size_t b = 0; b < n; ++b) {
      const double d = matrix[a * n + b];
      if (a == b) continue;
      if (!std::isfinite(d) || d < 0.0)
        return InvalidArgument("matrix: entries must be finite and >= 0");
      largest = std::max(largest, d);
    }
  }
  if (!options.exclusions.empty()) {
    return InvalidArgument("exclusions: the other layers' points are the exclusions");
  }
  for (const Vec2& p : points) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return InvalidArgument("points must be finite");
  }

  LayerVerifyReport report;
  for (size_t k = 0; k < n; ++k) {
    std::vector<Vec2> own;
    std::vector<ExclusionDisk> others;
    for (size_t p = 0; p < points.size(); ++p) {
      if (layer_of[p] == k) {
        own.push_back(points[p]);
      } else {
        others.push_back({points[p], matrix[layer_of[p] * n + k]});
      }
    }
    FieldVerifyOptions layer_options = options;
    layer_options.exclusions = others;
    StatusOr<FieldVerifyReport> judged = VerifyFieldWindow(own, window, fields[k], layer_options);
    if (!judged.ok()) return judged.status();
    report.layers.push_back(*judged);
  }

  // Pairs across layers: every pair closer than the largest D is found through the grid.
  if (largest > 0.0) {
    FieldPointGrid grid(Grown(window, 2.0 * largest), largest);
    for (const Vec2& p : points) grid.Add(p, 0.0);
    const std::vector<FieldPoint>& filed = grid.points();  // in input order
    for (size_t a = 0; a < filed.size(); ++a) {
      const Vec2 p = filed[a].p;
      const bool a_inside = window.Contains(p);
      grid.AnyNear(Grown(Rect{p.x, p.y, p.x, p.y}, largest), [&](const FieldPoint& q) {
        const auto b = static_cast<size_t>(&q - filed.data());
        if (b <= a || layer_of[a] == layer_of[b] || !(a_inside || window.Contains(q.p))) {
          return false;
        }
        const double d = matrix[layer_of[a] * n + layer_of[b]];
        const double dx = p.x - q.p.x;
        const double dy = p.y - q.p.y;
        const double d2 = dx * dx + dy * dy;
        if (!(d2 < largest * largest)) return false;
        ++report.cross_pairs_checked;
        if (d2 < d * d) ++report.cross_conflicts;
        if (d > 0.0 && std::sqrt(d2) / d < report.min_cross_ratio) {
          report.min_cross_ratio = std::sqrt(d2) / d;
          report.closest_cross_a = static_cast<int64_t>(a);
          report.closest_cross_b = static_cast<int64_t>(b);
        }
        return false;
      });
    }
  }
  return report;
}

}  // namespace scallop
