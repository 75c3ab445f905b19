// VerifyWorldRect: a halo query and the Delaunay verifier.
#include "scallop/plane/world_verifier.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "scallop/plane/world_layers.h"
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

// A layered world's window, judged by the layered verifier: each layer's rule as a field (a
// constant layer's as a constant one), the matrix D.
StatusOr<VerifyReport> VerifyLayeredWorldWindow(const PlanePoints& points, const Rect& rect,
                                                const WorldLayers& layers, double tolerance) {
  std::vector<RadiusField> fields;
  std::vector<double> matrix;
  for (int a = 0; a < layers.count(); ++a) {
    const World& layer = layers.world(a);
    fields.push_back(layer.radius_field() != nullptr ? *layer.radius_field()
                                                     : RadiusField::Constant(layer.min_distance()));
    for (int b = 0; b < layers.count(); ++b) matrix.push_back(layers.exclusion(a, b));
  }
  FieldVerifyOptions options;
  options.max_tolerance = tolerance;
  StatusOr<LayerVerifyReport> judged =
      VerifyLayeredWindow(points.positions, points.layers, rect, fields, matrix, options);
  if (!judged.ok()) return judged.status();
  VerifyReport report;
  report.spacing_violations = judged->cross_conflicts;
  report.pairs_checked = judged->cross_pairs_checked;
  report.maximal_ok = true;
  for (const FieldVerifyReport& layer : judged->layers) {
    report.points_checked += layer.points_checked;
    report.pairs_checked += layer.pairs_checked;
    report.spacing_violations += layer.conflicts;
    report.maximal_ok = report.maximal_ok && layer.maximal_ok;
  }
  report.spacing_ok = report.spacing_violations == 0;
  report.layered = *std::move(judged);
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
  const WorldLayers* layers = world.layers();
  // A layered world's halo also holds every point that can exclude a spot of the rectangle.
  const double halo = layers != nullptr
                          ? std::max(2 * layers->largest_spacing(), layers->largest_exclusion())
                          : 2 * world.max_spacing();
  const Rect grown = Grown(rect, halo);
  // Named "rect+halo" in messages: the rectangle verify reads.
  if (Status status = CheckQueryRect(world, grown, limit, "rect+halo"); !status.ok()) return status;
  StatusOr<PlanePoints> points = engine.Points(world, grown);
  if (!points.ok()) return points.status();
  if (inside) {
    for (size_t k = 0; k < points->positions.size(); ++k) {
      if (!rect.Contains(points->positions[k])) continue;
      inside->positions.push_back(points->positions[k]);
      inside->ids.push_back(points->ids[k]);
      if (!points->layers.empty()) inside->layers.push_back(points->layers[k]);
    }
  }
  const double max_abs =
      std::max({std::abs(grown.x0), std::abs(grown.x1), std::abs(grown.y0), std::abs(grown.y1)});
  if (layers != nullptr) {
    // A constant first layer is A3's, maximal up to its spacing margin; the field growth of the
    // later layers up to the field verifier's default.
    const double tolerance = std::max(FieldVerifyOptions{}.max_tolerance,
                                      MaximalityTolerance(world.min_distance(), max_abs));
    return VerifyLayeredWorldWindow(*points, rect, *layers, tolerance);
  }
  if (const RadiusField* field = world.radius_field()) {
    return VerifyFieldWorldWindow(points->positions, rect, *field, std::move(stop));
  }
  VerifyOptions options;
  options.seam_spacing = RegionLayout(world).side();
  options.max_tolerance = MaximalityTolerance(world.min_distance(), max_abs);
  options.stop = std::move(stop);
  return VerifyWindow(points->positions, rect, world.min_distance(), options);
}

}  // namespace scallop
