// VerifyWorldRect: a halo query and the Delaunay verifier.
#include "scallop/plane/world_verifier.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "scallop/sampling/spacing.h"

namespace scallop {
namespace {

// A field world's window, judged by the field verifier and told in VerifyReport's terms.
StatusOr<VerifyReport> VerifyFieldWorldWindow(const std::vector<Vec2>& points, const Rect& rect,
                                              const RadiusField& field,
                                              std::function<bool()> stop) {
  FieldVerifyOptions options;
  options.stop = std::move(stop);
  StatusOr<FieldVerifyReport> judged = VerifyFieldWindow(points, rect, field, options);
  if (!judged.ok()) return judged.status();
  VerifyReport report;
  report.points_checked = judged->points_checked;
  report.pairs_checked = judged->pairs_checked;
  report.spacing_violations = judged->conflicts;
  report.spacing_ok = judged->conflict_ok;
  report.maximal_ok = judged->maximal_ok;
  if (judged->closest_index_a >= 0) {
    report.closest_index_a = judged->closest_index_a;
    report.closest_index_b = judged->closest_index_b;
    report.closest_a = points[static_cast<size_t>(judged->closest_index_a)];
    report.closest_b = points[static_cast<size_t>(judged->closest_index_b)];
    report.min_distance = std::sqrt(SquaredDistance(report.closest_a, report.closest_b));
  }
  report.largest_empty_centre = judged->largest_gap_spot;
  report.field = *judged;
  return report;
}

}  // namespace

double MaximalityTolerance(double min_distance, double max_abs) {
  const double margin = (SpacingFor(min_distance, max_abs) - min_distance) / min_distance;
  return std::max(1e-9, 2 * margin);
}

StatusOr<VerifyReport> VerifyWorldRect(PlaneEngine& engine, const World& world, const Rect& rect,
                                       const QueryLimit& limit, PlanePoints* inside,
                                       std::function<bool()> stop) {
  if (Status status = CheckRectBounds(world, rect, "rect"); !status.ok()) return status;
  const Rect grown = Grown(rect, 2 * world.max_spacing());
  // Named "rect+halo" in messages: the rectangle verify reads.
  if (Status status = CheckQueryRect(world, grown, limit, "rect+halo"); !status.ok()) return status;
  StatusOr<PlanePoints> points = engine.Points(world, grown);
  if (!points.ok()) return points.status();
  if (inside) {
    for (size_t k = 0; k < points->positions.size(); ++k) {
      if (!rect.Contains(points->positions[k])) continue;
      inside->positions.push_back(points->positions[k]);
      inside->ids.push_back(points->ids[k]);
    }
  }
  if (const RadiusField* field = world.radius_field()) {
    return VerifyFieldWorldWindow(points->positions, rect, *field, std::move(stop));
  }
  VerifyOptions options;
  options.seam_spacing = RegionLayout(world).side();
  const double max_abs =
      std::max({std::abs(grown.x0), std::abs(grown.x1), std::abs(grown.y0), std::abs(grown.y1)});
  options.max_tolerance = MaximalityTolerance(world.min_distance(), max_abs);
  options.stop = std::move(stop);
  return VerifyWindow(points->positions, rect, world.min_distance(), options);
}

}  // namespace scallop
