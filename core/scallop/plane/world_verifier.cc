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

StatusOr<VerifyReport> VerifyWorldRect(PlaneEngine& engine, const World& world, const Rect& rect) {
  if (Status status = engine.ValidateQuery(world, rect); !status.ok()) return status;
  const double halo = 2 * world.min_distance;
  const Rect grown{rect.x0 - halo, rect.y0 - halo, rect.x1 + halo, rect.y1 + halo};
  StatusOr<PlanePoints> points = engine.Points(world, grown);
  if (!points.ok()) {
    return Status(points.status().code(),
                  points.status().message() + " (verify adds a halo of 2 * min_distance)");
  }
  VerifyOptions options;
  options.seam_spacing = RegionLayout(world.min_distance).side();
  const double max_abs = std::max({std::abs(grown.x0), std::abs(grown.x1), std::abs(grown.y0),
                                   std::abs(grown.y1)});
  options.max_tolerance = MaximalityTolerance(world.min_distance, max_abs);
  return VerifyWindow(points->positions, rect, world.min_distance, options);
}

}  // namespace scallop
