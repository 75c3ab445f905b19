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
  if (!header_written_) {
    out_ << std::setprecision(17) << CsvHeader(true, !radii.empty());
    header_written_ = true;
  }
  for (int k = 0; k < count; ++k) {
    out_ << decoded.ids[k] << ',' << decoded.positions[k].x << ',' << decoded.positions[k].y;
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
