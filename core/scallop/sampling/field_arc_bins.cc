// FieldArcBins' tables of ratios above 1.
#include "scallop/sampling/field_arc_bins.h"

namespace scallop {

const FieldArcBins::RatioTables& FieldArcBins::Tables() {
  static const RatioTables tables = Build();
  return tables;
}

FieldArcBins::RatioTables FieldArcBins::Build() {
  RatioTables tables;
  std::vector<ArcBins> least;
  for (int j = 0; j < kRatioTables; ++j) {
    const double low = 1.0 + static_cast<double>(j) / kStepsPerUnit;
    const double high = 1.0 + static_cast<double>(j + 1) / kStepsPerUnit;
    RatioTable& table = tables[static_cast<size_t>(j)];
    // Offsets up to (1 + high) t, and a cell more for rounding at the edge.
    table.half_cells = static_cast<int>(std::ceil(16.0 * (1.0 + high))) + 1;
    table.side = 2 * table.half_cells + 1;
    const auto cells = static_cast<size_t>(table.side * table.side);
    table.cells.resize(cells);
    least.resize(cells);
    BuildArcBinCells(low, 1e-7, table.half_cells, least.data());
    BuildArcBinCells(high, 1e-7, table.half_cells, table.cells.data());
    for (size_t c = 0; c < cells; ++c) table.cells[c].covered = least[c].covered;
  }
  return tables;
}

}  // namespace scallop
