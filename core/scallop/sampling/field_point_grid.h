// FieldPointGrid: the points of a radius-field run with their radii, filed in square cells so
// that conflict tests and coverage certificates visit only the points near a spot.
// Cells hold linked lists (head per cell, next per point): radii vary, so no fixed capacity fits.
#pragma once

#include <algorithm>
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
        head_(static_cast<size_t>(columns_ * rows_), -1) {}

  void Add(Vec2 p, double r) {
    const int64_t c = Column(p.x) + columns_ * Row(p.y);
    next_.push_back(head_[static_cast<size_t>(c)]);
    head_[static_cast<size_t>(c)] = static_cast<int32_t>(points_.size());
    points_.push_back({p, r});
  }

  const std::vector<FieldPoint>& points() const { return points_; }

  // Calls visit(const FieldPoint&) for every point filed in a cell that meets the window (a
  // superset of the points inside it); stops early when visit returns true, and returns
  // whether it did. O(cells met + points visited).
  template <typename Visit>
  bool AnyNear(const Rect& window, Visit visit) const {
    const int64_t c0 = Column(window.x0);
    const int64_t c1 = Column(window.x1);
    const int64_t r0 = Row(window.y0);
    const int64_t r1 = Row(window.y1);
    for (int64_t row = r0; row <= r1; ++row) {
      for (int64_t col = c0; col <= c1; ++col) {
        for (int32_t k = head_[static_cast<size_t>(col + columns_ * row)]; k >= 0;
             k = next_[static_cast<size_t>(k)]) {
          if (visit(points_[static_cast<size_t>(k)])) return true;
        }
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
  int64_t Column(double x) const {
    const double c = std::floor((x - area_.x0) * inverse_cell_);
    return static_cast<int64_t>(std::clamp(c, 0.0, static_cast<double>(columns_ - 1)));
  }
  int64_t Row(double y) const {
    const double r = std::floor((y - area_.y0) * inverse_cell_);
    return static_cast<int64_t>(std::clamp(r, 0.0, static_cast<double>(rows_ - 1)));
  }

  Rect area_;
  double inverse_cell_;
  int64_t columns_;
  int64_t rows_;
  std::vector<int32_t> head_;
  std::vector<int32_t> next_;
  std::vector<FieldPoint> points_;
};

}  // namespace scallop
