// ArcBins: which of the 64 bins of the key circle an arc covers whole, and
// which it meets at all. A3 drops at once the bins that some neighbour's arc
// covers (3 candidates in 10 keep none) and computes and cuts exactly only
// the arcs that meet a bin left over (1.6 of 7.5 a candidate, at 1M points).
#pragma once

#include <array>
#include <cstdint>

#include "scallop/geometry/vec2.h"
#include "scallop/sampling/available_boundary.h"

namespace scallop {

struct ArcBins {
  uint64_t covered;  // bit k: bin k lies inside the arc (none is claimed wrongly)
  uint64_t reached;  // bit k: the arc may meet bin k's inside (none is left out wrongly)
};

// The bins of the closed arc with these keys (in [0, 4]). O(1).
ArcBins BinsOf(const KeyArc& arc);

// The bins of the arc of a candidate's circle (radius s) that the disk of
// radius s about a neighbour at offset o covers, without computing the arc:
// looked up by o / s in a table of cells 1/16 s wide. `covered` holds only
// bins the arc covers for every offset in the cell, and `reached` every bin
// it meets for some offset there, both with a margin (1e-7, in units of s)
// far wider than rounding in the arc's computed keys (CoveredArcs), so they
// hold for those keys too (docs/design.md, A3, has the argument). The table
// (67 kB) is built once a process, in about 4 ms.
class NeighbourBins {
 public:
  explicit NeighbourBins(double spacing) : scale_(kCellsPerUnit / spacing), cells_(&Table()) {}

  // REQUIRES: SquaredLength(offset) < 4 s^2 (as A3's gather computes it). O(1).
  ArcBins Of(Vec2 offset) const {
    return (*cells_)[Cell(offset.y * scale_) * kSide + Cell(offset.x * scale_)];
  }

 private:
  static constexpr int kCells = 64;  // a side, over offsets from -2 s to 2 s
  // One more a side: an offset within rounding of 2 s lands in cell 64.
  static constexpr int kSide = kCells + 1;
  static constexpr double kCellsPerUnit = kCells / 4.0;
  using Cells = std::array<ArcBins, kSide * kSide>;

  // Without a clamp: |offset| < 2 s (to rounding) puts the sum in
  // (-1, kCells] at worst, and truncation takes a value just below 0 to 0.
  static int Cell(double scaled) { return static_cast<int>(scaled + kCells / 2); }
  static const Cells& Table();
  static Cells Build();

  double scale_;
  const Cells* cells_;
};

}  // namespace scallop
