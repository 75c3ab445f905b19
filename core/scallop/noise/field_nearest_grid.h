// FieldNearestGrid: one radius-field region's points plus a margin of 2.25 r_max of its
// neighbours', bucketed into square cells sized from the points' mean spacing, for finding
// the two nearest points of a position with a search that certifies its own answer. The
// constant worlds' NearestSearchGrid has cells of d and a fixed 3 d margin; a field world's
// spacing varies up to 100-fold within a region, so this grid searches rings of cells
// outwards until the answer is certified. See docs/noise.md, "Radius-field worlds".
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "scallop/geometry/rect.h"
#include "scallop/geometry/vec2.h"
#include "scallop/noise/nearest_search_grid.h"
#include "scallop/plane/region_layout.h"

namespace scallop {

class FieldNearestGrid {
 public:
  // The margin around the region, in units of r_max. On a field world without masks
  // F1 + F2 < 2 r_max (1 + tolerance) (docs/noise.md), so from any position of the region the
  // second distance stays inside a margin of 2 r_max; the extra quarter absorbs the rounding
  // slack many times over and keeps the 3 x 3 regions about the region enough (2.25 < 6).
  static constexpr double kMarginInRMax = 2.25;

  // The square the grid holds every world point of: `region` (of `layout`, a field world's)
  // grown by kMarginInRMax r_max on each side. Its edges are computed here only, so the
  // caller's query and the grid's certificate agree to the bit.
  static Rect CoveredSquare(const RegionLayout& layout, RegionKey region, double r_max);

  // Buckets `points` (ids[k] is the id of points[k]) lying in CoveredSquare; others are
  // ignored. For the search to be exact `points` must hold every world point of
  // CoveredSquare (clipped to the precision range: the world has none beyond it).
  // REQUIRES: layout of a field world, r_min and r_max its field's, ids.size() ==
  // points.size(), ids distinct. Cell side: sqrt(2 A / N) for N points in the square's area
  // A (about 2 points a cell), clamped to [r_min, 2 r_max], so a grid holds about N / 2
  // cells, and at least 36. Cost: O(points + cells).
  FieldNearestGrid(const RegionLayout& layout, RegionKey region, double r_min, double r_max,
                   std::span<const Vec2> points, std::span<const uint64_t> ids);

  // The two nearest points to p, in `best`, ordered by (squared distance, id) as
  // NearestSearchGrid orders them. Returns true only when the answer is certified: every
  // world point within the second distance of p lies inside the covered square and in the
  // cells examined. Returns false (best unspecified) when p is outside the grid's cells or the
  // second distance reaches past the covered square (possible near a masked area, where no
  // bound holds). Cost: rings of cells out to the second distance: about (F2 / cell + 1)^2
  // cells, a few dozen points where R is near the region's mean spacing; more where R is far
  // above it (up to (4 r_max / cell)^2 cells). Thread-safe (const).
  bool FindTwoNearest(const Vec2& p, TwoNearest& best) const;

  RegionKey key() const { return key_; }
  size_t PointCount() const { return ids_.size(); }
  double cell_side() const { return cell_; }
  int cells_per_side() const { return side_; }
  // Bytes held, for the lookup cache's budget.
  size_t Bytes() const;

 private:
  // Examines the points of cells [first, last] of one row.
  void ScanRow(int row, int first, int last, const Vec2& p, TwoNearest& best) const;

  RegionKey key_;
  Rect covered_;             // CoveredSquare
  double cell_ = 0;          // cell side
  double inverse_cell_ = 0;  // 1 / cell_, rounded
  double slack_ = 0;         // bound on rounding of cell coordinates and edges, world units
  int side_ = 0;             // cells per side
  std::vector<uint32_t> cell_start_;  // side_^2 + 1 offsets into the points (row-major)
  std::vector<Vec2> points_;          // bucketed by cell, input order within a cell
  std::vector<uint64_t> ids_;
};

}  // namespace scallop
