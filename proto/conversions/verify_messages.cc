// Verifier reports in and out of VerifyResponse.
#include "verify_messages.h"

namespace scallop {

v1::FieldVerifyResponse FieldVerifyToMessage(const FieldVerifyReport& report) {
  v1::FieldVerifyResponse out;
  out.set_conflicts(report.conflicts);
  out.set_min_spacing_ratio(report.min_spacing_ratio);
  out.set_largest_gap(report.largest_gap);
  out.set_largest_gap_x(report.largest_gap_spot.x);
  out.set_largest_gap_y(report.largest_gap_spot.y);
  out.set_gap_bound(report.gap_bound);
  out.set_points_masked(report.points_masked);
  out.set_passed(report.passed());
  return out;
}

FieldVerifyReport FieldVerifyFromMessage(const v1::FieldVerifyResponse& message, bool maximal_ok) {
  FieldVerifyReport report;
  report.conflicts = message.conflicts();
  report.min_spacing_ratio = message.min_spacing_ratio();
  report.largest_gap = message.largest_gap();
  report.largest_gap_spot = {message.largest_gap_x(), message.largest_gap_y()};
  report.gap_bound = message.gap_bound();
  report.points_masked = message.points_masked();
  report.conflict_ok = message.conflicts() == 0;
  report.maximal_ok = maximal_ok;
  return report;
}

v1::LayeredVerifyResponse LayeredVerifyToMessage(const LayerVerifyReport& report,
                                                 std::span<const std::string> names) {
  v1::LayeredVerifyResponse out;
  for (size_t k = 0; k < report.layers.size(); ++k) {
    v1::LayerVerifyResponse& layer = *out.add_layers();
    layer.set_name(k < names.size() ? names[k] : std::string());
    *layer.mutable_report() = FieldVerifyToMessage(report.layers[k]);
    layer.set_points_checked(report.layers[k].points_checked);
    layer.set_maximal_ok(report.layers[k].maximal_ok);
  }
  out.set_cross_pairs_checked(report.cross_pairs_checked);
  out.set_cross_conflicts(report.cross_conflicts);
  out.set_min_cross_ratio(report.min_cross_ratio);
  out.set_passed(report.passed());
  return out;
}

LayerVerifyReport LayeredVerifyFromMessage(const v1::LayeredVerifyResponse& message) {
  LayerVerifyReport report;
  for (const v1::LayerVerifyResponse& layer : message.layers()) {
    FieldVerifyReport own = FieldVerifyFromMessage(layer.report(), layer.maximal_ok());
    own.points_checked = layer.points_checked();
    report.layers.push_back(own);
  }
  report.cross_pairs_checked = message.cross_pairs_checked();
  report.cross_conflicts = message.cross_conflicts();
  report.min_cross_ratio = message.min_cross_ratio();
  return report;
}

}  // namespace scallop
