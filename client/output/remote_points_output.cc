// Chunk-by-chunk CSV of points from scallopd.
#include "client/output/remote_points_output.h"

#include <iomanip>

namespace scallop::cli {

int IncrementalCsv::Write(const v1::Points& points) {
  const int count = std::min({points.xs_size(), points.ys_size(), points.ids_size()});
  if (count == 0) return 0;
  const bool radii = points.radii_size() == count;
  if (!header_written_) {
    out_ << std::setprecision(17) << CsvHeader(true, radii);
    header_written_ = true;
  }
  for (int k = 0; k < count; ++k) {
    out_ << points.ids(k) << ',' << points.xs(k) << ',' << points.ys(k);
    if (radii) out_ << ',' << points.radii(k);
    out_ << '\n';
  }
  return count;
}

void IncrementalCsv::Finish() {
  if (!header_written_) out_ << CsvHeader(true, field_world_);
  header_written_ = true;
}

}  // namespace scallop::cli
