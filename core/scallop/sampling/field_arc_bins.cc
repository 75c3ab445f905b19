// FieldArcBins' tables of ratios above 1.
#include "scallop/sampling/field_arc_bins.h"

namespace scallop {

const FieldArcBins::RatioTables& FieldArcBins::Tables() {
  static const RatioTables tables = Build();
  return tables;
}

FieldArcBins::RatioTables FieldArcBins::Build() {
  // One table of bins at each bound 1 + j / kStepsPerUnit, all over offsets up to
  // (1 + kMaxRatio) t and a cell more for rounding at the edge; interval j takes its covered
  // bins from bound j and its reached bins from bound j + 1.
  const int half_cells = static_cast<int>(std::ceil(16.0 * (1.0 + kMaxRatio))) + 1;
  const int side = 2 * half_cells + 1;
  const auto cells = static_cast<size_t>(side * side);
  std::vector<ArcBins> at_bound(cells);
  RatioTables tables;
  for (int j = 0; j <= kRatioTables; ++j) {
    BuildArcBinCells(1.0 + static_cast<double>(j) / kStepsPerUnit, 1e-7, half_cells,
                     at_bound.data());
    if (j > 0) {
      // The reached bins of the interval below this bound.
      RatioTable& below = tables[static_cast<size_t>(j - 1)];
      for (size_t c = 0; c < cells; ++c) below.cells[c].reached = at_bound[c].reached;
    }
    if (j < kRatioTables) {
      RatioTable& table = tables[static_cast<size_t>(j)];
      table.half_cells = half_cells;
      table.side = side;
      table.cells.resize(cells);
      for (size_t c = 0; c < cells; ++c) table.cells[c].covered = at_bound[c].covered;
    }
  }
  return tables;
}

}  // namespace scallop
