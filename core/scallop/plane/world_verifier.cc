// VerifyWorldRect: a halo query and the Delaunay verifier.
#include "scallop/plane/world_verifier.h"

#include <algorithm>
#include <cmath>

#include "scallop/sampling/spacing.h"

namespace scallop {

double MaximalityTolerance(double min_distance, double max_abs) {
  const double margin = (SpacingFor(min_distance, max_abs) - min_distance) / min_distance;
  return std::max(1e-9, 2 * margin);
}

StatusOr<VerifyReport> VerifyWorldRect(PlaneEngine& engine, const World& world, const Rect& rect,
                                       const QueryLimit& limit, PlanePoints* inside,
                                       std::function<bool()> stop) {
  if (Status status = CheckRectBounds(world, rect, "rect"); !status.ok()) return status;
  const Rect grown = Grown(rect, 2 * world.min_distance());
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
  VerifyOptions options;
  options.seam_spacing = RegionLayout(world.min_distance()).side();
  const double max_abs =
      std::max({std::abs(grown.x0), std::abs(grown.x1), std::abs(grown.y0), std::abs(grown.y1)});
  options.max_tolerance = MaximalityTolerance(world.min_distance(), max_abs);
  options.stop = std::move(stop);
  return VerifyWindow(points->positions, rect, world.min_distance(), options);
}

}  // namespace scallop
