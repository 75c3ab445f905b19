// Chunk-by-chunk CSV of points from scallopd.
#include "client/output/remote_points_output.h"

#include <iomanip>
#include <vector>

#include "world_messages.h"

namespace scallop::cli {

StatusOr<int> IncrementalCsv::Write(const v1::Points& points) {
  PlanePoints decoded;
  std::vector<double> radii;
  if (Status status = ReadPoints(points, decoded, &radii); !status.ok()) return status;
  const auto count = static_cast<int>(decoded.ids.size());
  if (count == 0) return 0;
  const bool with_layers = !decoded.layers.empty();
  if (with_layers && names_.empty()) {
    StatusOr<std::vector<std::string>> names =
        layer_names_ ? layer_names_()
                     : StatusOr<std::vector<std::string>>(
                           InvalidArgument("points: layers of an unknown world"));
    if (!names.ok()) return names.status();
    names_ = std::move(*names);
  }
  for (const uint8_t layer : decoded.layers) {
    if (layer >= names_.size()) return InvalidArgument("points: a layer the world does not have");
  }
  if (!header_written_) {
    out_ << std::setprecision(17) << CsvHeader(true, !radii.empty(), with_layers);
    header_written_ = true;
  }
  for (int k = 0; k < count; ++k) {
    out_ << decoded.ids[k] << ',' << decoded.positions[k].x << ',' << decoded.positions[k].y;
    if (with_layers) out_ << ',' << names_[decoded.layers[k]];
    if (!radii.empty()) out_ << ',' << radii[k];
    out_ << '\n';
  }
  return count;
}

void IncrementalCsv::Finish() {
  if (!header_written_) out_ << CsvHeader(true, field_world_);
  header_written_ = true;
}

}  // namespace scallop::cli
