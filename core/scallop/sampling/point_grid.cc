// PointGrid construction and torus wrapping.
#include "scallop/sampling/point_grid.h"

namespace scallop {

PointGrid::PointGrid(const Rect& area, bool torus, double min_distance, double margin)
    : origin_{area.x0 - margin, area.y0 - margin},
      torus_(torus),
      width_(area.Width() + 2 * margin),
      height_(area.Height() + 2 * margin) {
  // A cell must be strictly narrower than d / sqrt(2) so that its diagonal is
  // shorter than d; on a torus it must also divide the sides exactly.
  const double widest = min_distance / std::sqrt(2.0) * (1.0 - 1e-9);
  columns_ = std::max<int64_t>(1, static_cast<int64_t>(std::ceil(width_ / widest)));
  rows_ = std::max<int64_t>(1, static_cast<int64_t>(std::ceil(height_ / widest)));
  if (torus_) {
    // Cells tile each side exactly, so wrapping a cell index wraps the plane.
    cell_width_ = width_ / static_cast<double>(columns_);
    cell_height_ = height_ / static_cast<double>(rows_);
  } else {
    cell_width_ = cell_height_ = widest;
    // One extra row and column absorb points on the far edge of the margin.
    columns_ = static_cast<int64_t>(std::floor(width_ / widest)) + 1;
    rows_ = static_cast<int64_t>(std::floor(height_ / widest)) + 1;
  }
  cells_.resize(static_cast<size_t>(columns_ * rows_));
}

Vec2 PointGrid::WrapIntoDomain(Vec2 p) const {
  if (!torus_) return p;
  double x = p.x, y = p.y;
  const double x1 = origin_.x + width_, y1 = origin_.y + height_;
  if (x < origin_.x) x += width_;
  if (x >= x1) x -= width_;
  if (y < origin_.y) y += height_;
  if (y >= y1) y -= height_;
  // Rounding can land exactly on the far edge after adding the width.
  if (x >= x1) x = std::nextafter(x1, origin_.x);
  if (y >= y1) y = std::nextafter(y1, origin_.y);
  return {x, y};
}

}  // namespace scallop
