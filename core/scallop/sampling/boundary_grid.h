// BoundaryGrid: A3's neighbour grid on a rectangle. PointGrid's cells (same
// origin, width and count), but laid out for A3's one query, the 7 x 7 cells
// around a candidate: positions only, 16 bytes a cell instead of 24, in tiles
// of 8 x 8 cells so that the query touches at most 4 tiles (at 1M points a
// PointGrid row is about 10 pages, and the query touched 7 of them).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "scallop/geometry/rect.h"
#include "scallop/geometry/vec2.h"

namespace scallop {

class BoundaryGrid {
 public:
  // Covers `area` grown by `margin` on every side, with the cells
  // PointGrid(area, false, min_distance, margin) has. REQUIRES: min_distance > 0.
  BoundaryGrid(const Rect& area, double min_distance, double margin)
      : origin_{area.x0 - margin, area.y0 - margin} {
    // PointGrid's expressions, so that every point falls in the same cell.
    const double width = area.Width() + 2 * margin, height = area.Height() + 2 * margin;
    cell_size_ = min_distance / std::sqrt(2.0) * (1.0 - 1e-9);
    columns_ = static_cast<int64_t>(std::floor(width / cell_size_)) + 1;
    rows_ = static_cast<int64_t>(std::floor(height / cell_size_)) + 1;
    tile_columns_ = (columns_ + kTile - 1) / kTile;
    const int64_t tile_rows = (rows_ + kTile - 1) / kTile;
    positions_.resize(static_cast<size_t>(tile_columns_ * tile_rows * kTile * kTile), kEmpty);
  }

  // As PointGrid::Insert, but only the position is kept. REQUIRES: p within
  // the covered area and no point closer than min_distance already stored
  // (so every stored point is alone in its cell, and it is the only point there).
  void Insert(int32_t /*index*/, Vec2 p) { positions_[CellIndex(ColumnOf(p.x), RowOf(p.y))] = p; }

  // What PointGrid::GatherNear gives on a rectangle: the positions of the
  // stored points other than point `self` with SquaredLength(q - p) <
  // limit_squared, among the cells within `radius` of p, in row-major order.
  // REQUIRES: self < 0 (no point excluded), or p is the position of stored
  // point self. Non-const only because the query hides that point while it
  // scans. O((radius / cell)^2), without a branch per cell.
  size_t GatherNear(Vec2 p, double radius, double limit_squared, int32_t self,
                    std::vector<Vec2>& out) {
    // Truncation is floor here: negatives are clamped to 0 either way.
    const int64_t c0 = std::max<int64_t>(TruncatedColumnOf(p.x - radius), 0);
    const int64_t c1 = std::min<int64_t>(TruncatedColumnOf(p.x + radius), columns_ - 1);
    const int64_t r0 = std::max<int64_t>(TruncatedRowOf(p.y - radius), 0);
    const int64_t r1 = std::min<int64_t>(TruncatedRowOf(p.y + radius), rows_ - 1);
    if (c0 > c1 || r0 > r1) return 0;
    const auto most = static_cast<size_t>((r1 - r0 + 1) * (c1 - c0 + 1));
    if (out.size() < most) out.resize(most);
    // Point `self` is alone in p's own cell (Insert's REQUIRES): hide it there
    // for the scan, instead of a test per cell.
    const size_t own = CellIndex(std::clamp<int64_t>(TruncatedColumnOf(p.x), 0, columns_ - 1),
                                 std::clamp<int64_t>(TruncatedRowOf(p.y), 0, rows_ - 1));
    const Vec2 saved = positions_[own];
    if (self >= 0) positions_[own] = kEmpty;
    // Columns [c0, c1] fall in at most two tiles: `split` starts the second.
    const int64_t split = std::min<int64_t>((c0 | (kTile - 1)) + 1, c1 + 1);
    size_t kept = 0;
    for (int64_t r = r0; r <= r1; ++r) {
      const Vec2* row = &positions_[CellIndex(0, r)];  // row r of the first tile column
      kept = Scan(row, c0, split, p, limit_squared, out, kept);
      kept = Scan(row, split, c1 + 1, p, limit_squared, out, kept);
    }
    positions_[own] = saved;
    return kept;
  }

  Vec2 NearestImage(Vec2, Vec2 q) const { return q; }
  Vec2 WrapIntoDomain(Vec2 p) const { return p; }

 private:
  static constexpr int64_t kTile = 8;  // cells a side of a tile: 8 x 8 x 16 bytes = 1 KiB
  // Infinite: an empty cell fails the distance test without a test of its own.
  static constexpr Vec2 kEmpty{std::numeric_limits<double>::infinity(),
                               std::numeric_limits<double>::infinity()};

  // Columns [begin, end) (within one tile) of the row whose first tile's
  // cells start at `row`: every cell written to out, a kept one advances.
  static size_t Scan(const Vec2* row, int64_t begin, int64_t end, Vec2 p, double limit_squared,
                     std::vector<Vec2>& out, size_t kept) {
    if (begin >= end) return kept;
    const Vec2* cell = row + (begin / kTile) * kTile * kTile + begin % kTile;
    for (int64_t c = begin; c < end; ++c, ++cell) {
      out[kept] = *cell;
      kept += SquaredLength(*cell - p) < limit_squared;
    }
    return kept;
  }

  int64_t ColumnOf(double x) const {
    return static_cast<int64_t>(std::floor((x - origin_.x) / cell_size_));
  }
  int64_t RowOf(double y) const {
    return static_cast<int64_t>(std::floor((y - origin_.y) / cell_size_));
  }
  // ColumnOf and RowOf where the quotient is not negative; towards zero otherwise.
  int64_t TruncatedColumnOf(double x) const {
    return static_cast<int64_t>((x - origin_.x) / cell_size_);
  }
  int64_t TruncatedRowOf(double y) const {
    return static_cast<int64_t>((y - origin_.y) / cell_size_);
  }
  size_t CellIndex(int64_t column, int64_t row) const {
    const int64_t tile = (row / kTile) * tile_columns_ + column / kTile;
    return static_cast<size_t>(tile * kTile * kTile + (row % kTile) * kTile + column % kTile);
  }

  Vec2 origin_;
  double cell_size_;
  int64_t columns_, rows_, tile_columns_;
  std::vector<Vec2> positions_;
};

}  // namespace scallop
