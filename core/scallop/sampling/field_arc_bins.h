// FieldArcBins: the bins (arc_bins.h) of the arc a field candidate's neighbour cuts from the
// candidate's circle (DiskArc: circle of radius t = R(p), disk of radius m = max(R(p), R(q))),
// looked up by the offset and the ratio m / t instead of computed, so that the growth computes
// and cuts exactly only the arcs that meet a bin some other arc has not covered, as A3 does.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "scallop/geometry/vec2.h"
#include "scallop/sampling/arc_bins.h"

namespace scallop {

class FieldArcBins {
 public:
  // Ratios m / t above this get no table: Of answers "covers none, may meet all".
  static constexpr double kMaxRatio = 2.0;
  // Tables a unit of ratio above 1: ratio intervals (1 + (j - 1) / 2, 1 + j / 2]. (Four a
  // unit computed 1.86 exact arcs a candidate instead of 2.03 at r_max / r_min = 8, about 1 ms
  // a million points, and took 35 ms longer to build.)
  static constexpr int kStepsPerUnit = 2;
  static constexpr int kRatioTables = 2;  // (kMaxRatio - 1) kStepsPerUnit

  // For the candidate circle of radius t. O(1) (the tables, about 310 kB, are built at the
  // first use in a process, in about 40 ms).
  explicit FieldArcBins(double t);

  // The bins of the arc DiskArc(offset, t, m, ...) computes, for ratio = m / t (as computed):
  // `covered` holds only bins the computed arc holds whole, `reached` every bin whose inside
  // it meets. Ratio 1 (m = t) reads A3's table (NeighbourBins); a ratio in
  // (1 + (j - 1) / 2, 1 + j / 2] reads a table whose covered bins are those of the disk of the
  // interval's least ratio and whose reached bins those of its largest: a larger disk covers
  // more of the circle, so both claims hold for every ratio between, with the tables' margin
  // (1e-7 in g, in units of t^2) far above rounding in the ratio and in DiskArc's keys.
  // REQUIRES: m >= t, SquaredLength(offset) < (t + m)^2 as computed, offset not zero. O(1).
  ArcBins Of(Vec2 offset, double ratio) const;

 private:
  // Cells 1/16 of t wide over offsets from -half_cells / 16 to half_cells / 16 (in units of t),
  // row-major from the lowest.
  struct RatioTable {
    int half_cells = 0;
    int side = 0;
    std::vector<ArcBins> cells;
  };
  using RatioTables = std::array<RatioTable, kRatioTables>;
  static const RatioTables& Tables();
  static RatioTables Build();

  NeighbourBins equal_;
  double inverse_cell_;  // 16 / t: the tables' cells are 1/16 of the circle's radius
  const RatioTables* tables_;
};

inline FieldArcBins::FieldArcBins(double t)
    : equal_(t), inverse_cell_(16.0 / t), tables_(&Tables()) {}

// In the header, for the compiler to inline: it runs for every neighbour of every candidate.
inline ArcBins FieldArcBins::Of(Vec2 offset, double ratio) const {
  if (!(ratio > 1.0)) return equal_.Of(offset);
  const double steps = (ratio - 1.0) * kStepsPerUnit;
  if (!(steps <= kRatioTables)) return {0, ~uint64_t{0}};
  const RatioTable& table = (*tables_)[static_cast<size_t>(std::ceil(steps)) - 1];
  const auto cell = [&](double v) {
    return std::clamp(static_cast<int>(v * inverse_cell_ + table.half_cells), 0, table.side - 1);
  };
  return table.cells[static_cast<size_t>(cell(offset.y) * table.side + cell(offset.x))];
}

}  // namespace scallop
