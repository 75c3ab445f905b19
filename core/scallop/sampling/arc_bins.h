// ArcBins: which of the 64 bins of the key circle an arc covers whole, and
// which it meets at all. A3 drops at once the bins that some neighbour's arc
// covers (3 candidates in 10 keep none) and computes and cuts exactly only
// the arcs that meet a bin left over (1.6 of 7.5 a candidate, at 1M points).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

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
  // Of(q - centre), with both coordinates in the lanes of one register: the same operations
  // on each, so the same cell, in fewer instructions (A3 asks for 7.5 a candidate).
  ArcBins Of(Vec2 q, Vec2 centre) const {
#if defined(__SSE2__)
    const Doubles scaled =
        (Doubles{q.x, q.y} - Doubles{centre.x, centre.y}) * Doubles{scale_, scale_} +
        Doubles{kCells / 2, kCells / 2};
    // Truncation towards zero in both lanes, as Cell's cast.
    const auto both = static_cast<uint64_t>(_mm_cvtsi128_si64(_mm_cvttpd_epi32(scaled)));
    const auto column = static_cast<int32_t>(both), row = static_cast<int32_t>(both >> 32);
    return (*cells_)[row * kSide + column];
#else
    return Of(q - centre);
#endif
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

// The bins of the arc of a circle of radius rho that a disk of radius lambda rho covers, for
// one ratio lambda: NeighbourBins' table for disks of another radius than the circle's (the
// second intersection rule, CoveredArcOfCircle), such as a layered world's exclusion disks seen
// from A3's circles. Looked up by offset / rho in cells 1/16 rho wide over offsets up to
// (1 + lambda) rho. Conservative for the arcs CoveredArcOfCircle computes with any disk radius
// within a factor 1 +- kDiskBinsRatioSlack of lambda rho (the margins samplers add to radii
// move the ratio by less), with the margin 1e-7 + lambda^2 2^-13 in g.
class DiskBins {
 public:
  // Ratios up to this get a table (97 x 97 cells at 2, about 150 kB, built in about 10 ms).
  static constexpr double kMaxRatio = 2.0;
  // At most this many ratios get a table in a process; later ones get none.
  static constexpr int kMaxTables = 32;
  static constexpr double kRatioSlack = 0x1.0p-14;

  // The table for `ratio`, built at the first call for that ratio and kept for the process (a
  // pure function of the ratio, as NeighbourBins' table; thread-safe); null above kMaxRatio,
  // for a ratio not above 0, or once kMaxTables ratios have tables: then the caller computes
  // the arcs exactly, with the same result.
  static const DiskBins* ForRatio(double ratio);

  // The bins for the disk at `offset` from the circle's centre, with inverse_cell = 16 / rho.
  // REQUIRES: |offset| < rho + disk radius (as computed in doubles). O(1).
  ArcBins Of(Vec2 offset, double inverse_cell) const {
    const auto cell = [&](double v) {
      return std::clamp(static_cast<int>(v * inverse_cell + half_cells_), 0, side_ - 1);
    };
    return cells_[static_cast<size_t>(cell(offset.y) * side_ + cell(offset.x))];
  }

 private:
  explicit DiskBins(double ratio);

  int half_cells_, side_;
  std::vector<ArcBins> cells_;
};

// Fills the side x side cells (side = 2 half_cells + 1, row-major from the lowest offsets) of a
// table of bins for disks of radius `ratio` (in units of the circle's radius) over offsets from
// -half_cells / 16 on, 1/16 a cell; covered bins only where g >= margin over the whole cell and
// bin, reached wherever g >= -margin may hold. NeighbourBins (ratio 1, margin 1e-7, 32) and
// DiskBins build their tables with it.
void BuildArcBinCells(double ratio, double margin, int half_cells, ArcBins* cells);

}  // namespace scallop
