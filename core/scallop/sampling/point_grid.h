// PointGrid: the uniform grid every sampler uses to find the points near a
// spot in O(1). Cells are a little under d / sqrt(2) wide, so a set whose
// points are at least d apart has at most one point per cell.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "scallop/geometry/rect.h"
#include "scallop/geometry/vec2.h"

namespace scallop {

class PointGrid {
 public:
  // Covers `area` grown by `margin` on every side (margin 0 on a torus, whose
  // cells wrap around). REQUIRES: min_distance > 0; on a torus every side of
  // `area` is at least 8 * min_distance, so a neighbour query of radius up to
  // 4 d sees each point once, at its image nearest to the query spot.
  PointGrid(const Rect& area, bool torus, double min_distance, double margin = 0.0);

  // Stores point `index` at `p`. REQUIRES: p within the covered area and no
  // point closer than min_distance already stored (so its cell is free).
  void Insert(int32_t index, Vec2 p) {
    Cell& cell = cells_[CellIndex(ColumnOf(p.x), RowOf(p.y))];
    cell.position = p;
    cell.index = index;
  }

  // Forgets the point stored at `p` (its cell is free again). REQUIRES: p is a stored position.
  void Remove(Vec2 p) { cells_[CellIndex(ColumnOf(p.x), RowOf(p.y))].index = -1; }

  // Calls visit(index, position) for every stored point that may lie within
  // `radius` of `p` (a superset: the caller measures). On a torus `position`
  // is the image of the point nearest to `p`. O((radius / cell)^2).
  template <typename Visit>
  void ForEachNear(Vec2 p, double radius, Visit&& visit) const {
    const int64_t c0 = ColumnOf(p.x - radius), c1 = ColumnOf(p.x + radius);
    const int64_t r0 = RowOf(p.y - radius), r1 = RowOf(p.y + radius);
    if (!torus_) {
      for (int64_t r = std::max<int64_t>(r0, 0); r <= std::min<int64_t>(r1, rows_ - 1); ++r) {
        const Cell* row = &cells_[static_cast<size_t>(r * columns_)];
        for (int64_t c = std::max<int64_t>(c0, 0); c <= std::min<int64_t>(c1, columns_ - 1); ++c) {
          if (row[c].index >= 0) visit(row[c].index, row[c].position);
        }
      }
      return;
    }
    // On a torus visit each distinct cell once and shift its point to the image nearest p.
    const int64_t row_count = std::min<int64_t>(r1 - r0 + 1, rows_);
    const int64_t column_count = std::min<int64_t>(c1 - c0 + 1, columns_);
    for (int64_t dr = 0; dr < row_count; ++dr) {
      const int64_t r = Wrap(r0 + dr, rows_);
      for (int64_t dc = 0; dc < column_count; ++dc) {
        const Cell& cell = cells_[CellIndex(Wrap(c0 + dc, columns_), r)];
        if (cell.index >= 0) visit(cell.index, NearestImage(p, cell.position));
      }
    }
  }

  // Writes to out[0, n) and returns n: the positions (nearest images on a
  // torus) of the stored points other than point `self` whose squared
  // distance to p, SquaredLength(q - p) in double precision, is below
  // `limit_squared`, in ForEachNear's order. `out` is scratch: it only ever
  // grows. A3 uses it on tori; on rectangles A3 has BoundaryGrid, whose
  // tests take this as the plain answer. REQUIRES: limit_squared <= radius^2.
  // O((radius / cell)^2).
  size_t GatherNear(Vec2 p, double radius, double limit_squared, int32_t self,
                    std::vector<Vec2>& out) const {
    const int64_t c0 = ColumnOf(p.x - radius), c1 = ColumnOf(p.x + radius);
    const int64_t r0 = RowOf(p.y - radius), r1 = RowOf(p.y + radius);
    const auto most = static_cast<size_t>((r1 - r0 + 1) * (c1 - c0 + 1));
    if (out.size() < most) out.resize(most);
    size_t kept = 0;
    ForEachNear(p, radius, [&](int32_t index, Vec2 q) {
      if (index != self && SquaredLength(q - p) < limit_squared) out[kept++] = q;
    });
    return kept;
  }

  // The image of q (under the torus's translations) nearest to p; q itself
  // on a rectangle.
  Vec2 NearestImage(Vec2 p, Vec2 q) const {
    if (!torus_) return q;
    return {q.x + width_ * std::round((p.x - q.x) / width_),
            q.y + height_ * std::round((p.y - q.y) / height_)};
  }

  // Wraps p into the half-open torus rectangle; p itself on a rectangle.
  Vec2 WrapIntoDomain(Vec2 p) const;

  size_t cell_count() const { return cells_.size(); }

 private:
  struct Cell {
    Vec2 position;
    int32_t index = -1;
  };

  int64_t ColumnOf(double x) const {
    return static_cast<int64_t>(std::floor((x - origin_.x) / cell_width_));
  }
  int64_t RowOf(double y) const {
    return static_cast<int64_t>(std::floor((y - origin_.y) / cell_height_));
  }
  static int64_t Wrap(int64_t i, int64_t n) { return ((i % n) + n) % n; }
  size_t CellIndex(int64_t column, int64_t row) const {
    if (torus_) {
      column = Wrap(column, columns_);
      row = Wrap(row, rows_);
    }
    return static_cast<size_t>(row * columns_ + column);
  }

  Vec2 origin_;
  bool torus_;
  double width_, height_;
  double cell_width_, cell_height_;
  int64_t columns_, rows_;
  std::vector<Cell> cells_;
};

}  // namespace scallop
