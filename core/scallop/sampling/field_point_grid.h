// FieldPointGrid: the points of a radius-field run with their radii, filed in square cells so
// that conflict tests and coverage certificates visit only the points near a spot.
// Cells hold linked lists (head per cell, next per point): radii vary, so no fixed capacity fits.
// Pack() copies the points filed so far into one array ordered by cell, row-major, so that a
// search reads a row of its window as one run of memory, whatever the cells' counts (most
// cells of a wide window are empty), rather than following lists across points(): a run's
// points are placed in no spatial order, and walking the lists was a cache miss a point.
// Points added after a Pack go to the lists; a bit per cell and a count per row say where
// there are any, so that a row without them is read as its packed run alone.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "scallop/geometry/rect.h"
#include "scallop/geometry/vec2.h"

namespace scallop {

struct FieldPoint {
  Vec2 p;
  double r;  // R(p), evaluated once when the point was placed
};

// Not thread-safe for writes; concurrent reads are fine.
class FieldPointGrid {
 public:
  // `area` holds every point ever added; `cell` is the cell side. REQUIRES: the cell count
  // (area / cell^2) fits in memory; the caller bounds it.
  FieldPointGrid(const Rect& area, double cell)
      : area_(area),
        inverse_cell_(1.0 / cell),
        columns_(std::max<int64_t>(1, static_cast<int64_t>(std::ceil(area.Width() / cell)))),
        rows_(std::max<int64_t>(1, static_cast<int64_t>(std::ceil(area.Height() / cell)))),
        words_per_row_((columns_ + 63) / 64),
        head_(static_cast<size_t>(columns_ * rows_), -1),
        listed_(static_cast<size_t>(words_per_row_ * rows_), 0),
        listed_in_row_(static_cast<size_t>(rows_), 0) {}

  void Add(Vec2 p, double r) {
    const int64_t col = Column(p.x);
    const int64_t row = Row(p.y);
    const auto c = static_cast<size_t>(col + columns_ * row);
    next_.push_back(head_[c]);
    head_[c] = static_cast<int32_t>(points_.size());
    listed_[static_cast<size_t>(row * words_per_row_ + col / 64)] |= uint64_t{1} << (col % 64);
    ++listed_in_row_[static_cast<size_t>(row)];
    points_.push_back({p, r});
  }

  const std::vector<FieldPoint>& points() const { return points_; }

  // Moves every point filed so far into the packed array (cells in row-major order, each cell's
  // points in the order they were added); points added later go to the lists as before. Changes
  // only the order in which AnyNear visits a cell's points. O(points + cells): the lists' heads
  // are cleared by their points (those added since the last Pack), and the points are scattered
  // through the cells' starts themselves, with no cell-sized copy to fault in at every Pack.
  void Pack() {
    const size_t cells = head_.size();
    for (size_t k = packed_.size(); k < points_.size(); ++k) {
      const Vec2 p = points_[k].p;
      const int64_t row = Row(p.y);
      head_[static_cast<size_t>(Column(p.x) + columns_ * row)] = -1;
      listed_[static_cast<size_t>(row * words_per_row_ + Column(p.x) / 64)] = 0;
      listed_in_row_[static_cast<size_t>(row)] = 0;
    }
    cell_start_.assign(cells + 1, 0);
    for (const FieldPoint& q : points_) ++cell_start_[CellOf(q.p) + 1];
    for (size_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
    packed_.resize(points_.size());
    // Each point goes to its cell's next free place; cell_start_[c] runs up to the next cell's
    // start meanwhile, and is moved back one cell after.
    for (const FieldPoint& q : points_)
      packed_[static_cast<size_t>(cell_start_[CellOf(q.p)]++)] = q;
    for (size_t c = cells; c > 0; --c) cell_start_[c] = cell_start_[c - 1];
    cell_start_[0] = 0;
  }

  // How many points Pack() last moved (0 before the first).
  size_t packed_count() const { return packed_.size(); }

  // Calls visit(const FieldPoint&) (a reference into points() or into the packed copy) for every
  // point filed in a cell that meets the window (a superset of the points inside it), row by row
  // from the bottom, each row by column, a cell's packed points in the order they were added and
  // then its listed ones, newest first; stops early when visit returns true, and returns whether
  // it did. The order is part of what the field sampler computes (the first conflicting point
  // found is the one whose arc a refused try cuts). O(rows + points visited + listed cells).
  template <typename Visit>
  bool AnyNear(const Rect& window, Visit visit) const {
    const int64_t c0 = Column(window.x0);
    const int64_t c1 = Column(window.x1);
    const int64_t r0 = Row(window.y0);
    const int64_t r1 = Row(window.y1);
    const bool packed = !cell_start_.empty();
    for (int64_t row = r0; row <= r1; ++row) {
      const int64_t base = columns_ * row;
      // The row's packed points run from the start of cell c0 to the end of cell c1; each
      // listed cell's lists go right after its packed points.
      int32_t k = packed ? cell_start_[static_cast<size_t>(base + c0)] : 0;
      if (listed_in_row_[static_cast<size_t>(row)] != 0) {
        for (int64_t first = c0; first <= c1; first += 64) {
          const int64_t width = std::min<int64_t>(64, c1 - first + 1);
          for (uint64_t bits = ListedBits(row, first, width); bits != 0; bits &= bits - 1) {
            const auto c = static_cast<size_t>(base + first + std::countr_zero(bits));
            if (packed && VisitPacked(k, cell_start_[c + 1], visit)) return true;
            if (VisitListed(c, visit)) return true;
          }
        }
      }
      if (packed && VisitPacked(k, cell_start_[static_cast<size_t>(base + c1 + 1)], visit)) {
        return true;
      }
    }
    return false;
  }

  // The conflict rule: true when some point q has |x - q|^2 < max(rx, R(q))^2 in doubles, the
  // very expression the verifier evaluates. Points farther than `reach` are not looked at, so
  // the caller passes a reach no conflict can exceed.
  bool Conflicts(Vec2 x, double rx, double reach) const {
    return AnyNear(Grown(Rect{x.x, x.y, x.x, x.y}, reach), [&](const FieldPoint& q) {
      const double dx = x.x - q.p.x;
      const double dy = x.y - q.p.y;
      const double m = std::max(rx, q.r);
      return dx * dx + dy * dy < m * m;
    });
  }

 private:
  // floor((x - x0) / cell) clamped to the columns, without the floor: clamped to [0, columns)
  // first, the value is not negative, and the conversion's truncation is then floor (a value
  // below 0 clamps to 0 either way). std::floor costs a call or a long sequence without SSE4.1.
  int64_t Column(double x) const { return Clamped((x - area_.x0) * inverse_cell_, columns_); }
  int64_t Row(double y) const { return Clamped((y - area_.y0) * inverse_cell_, rows_); }
  static int64_t Clamped(double v, int64_t count) {
    return static_cast<int64_t>(std::clamp(v, 0.0, static_cast<double>(count - 1)));
  }

  // Bits first .. first + width - 1 (width in [1, 64]) of the row's listed cells, bit 0 first's.
  uint64_t ListedBits(int64_t row, int64_t first, int64_t width) const {
    const uint64_t* words = listed_.data() + row * words_per_row_;
    const int64_t w = first / 64;
    const int shift = static_cast<int>(first % 64);
    uint64_t bits = words[w] >> shift;
    if (shift != 0 && w + 1 < words_per_row_) bits |= words[w + 1] << (64 - shift);
    return width == 64 ? bits : bits & ((uint64_t{1} << width) - 1);
  }

  size_t CellOf(Vec2 p) const { return static_cast<size_t>(Column(p.x) + columns_ * Row(p.y)); }

  // Visits cell c's listed points, newest first; true when visit stopped.
  template <typename Visit>
  bool VisitListed(size_t c, Visit& visit) const {
    for (int32_t j = head_[c]; j >= 0; j = next_[static_cast<size_t>(j)]) {
      if (visit(points_[static_cast<size_t>(j)])) return true;
    }
    return false;
  }

  // Visits packed_[k, end), k moved past each point visited; true when visit stopped.
  template <typename Visit>
  bool VisitPacked(int32_t& k, int32_t end, Visit& visit) const {
    for (; k < end; ++k) {
      if (visit(packed_[static_cast<size_t>(k)])) return true;
    }
    return false;
  }

  Rect area_;
  double inverse_cell_;
  int64_t columns_;
  int64_t rows_;
  int64_t words_per_row_;
  std::vector<int32_t> head_;
  // Cells with listed points (added since the last Pack): bit col % 64 of word
  // row * words_per_row_ + col / 64; and how many a row holds.
  std::vector<uint64_t> listed_;
  std::vector<int32_t> listed_in_row_;
  std::vector<int32_t> next_;  // per point: the next listed point of its cell, or -1
  std::vector<FieldPoint> points_;
  // After Pack(): the packed points of cell c are packed_[cell_start_[c], cell_start_[c + 1]).
  std::vector<int32_t> cell_start_;
  std::vector<FieldPoint> packed_;
};

}  // namespace scallop
