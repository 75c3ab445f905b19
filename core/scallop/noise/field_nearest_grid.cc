// FieldNearestGrid: bucketing by counting sort, and the ring search with its certificate
// (the cells examined and the covered square must both hold the second distance).
#include "scallop/noise/field_nearest_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace scallop {
namespace {

// Rounding slack in units of r_min. Within the precision range (2^32 r_min) one ulp of a
// coordinate is at most 2^-20 r_min, and a cell coordinate (x - origin) / cell, at most
// about 1,100 cells, adds 2^-41 cells of at most 2 r_max = 200 r_min: both far below
// 2^-12 r_min, as for the constant grids (docs/noise.md, "Why a certified answer is exact").
constexpr double kSlackInRMin = 0x1.0p-12;

// Mean points per cell the side aims at: few enough that p's own cells are cheap where R is
// near the mean, enough that sparse parts need few rings.
constexpr double kPointsPerCell = 2.0;

}  // namespace

Rect FieldNearestGrid::CoveredSquare(const RegionLayout& layout, RegionKey region, double r_max) {
  const Rect owned = layout.RegionRect(region);
  const double margin = kMarginInRMax * r_max;
  return {owned.x0 - margin, owned.y0 - margin, owned.x1 + margin, owned.y1 + margin};
}

FieldNearestGrid::FieldNearestGrid(const RegionLayout& layout, RegionKey region, double r_min,
                                   double r_max, std::span<const Vec2> points,
                                   std::span<const uint64_t> ids)
    : key_(region), covered_(CoveredSquare(layout, region, r_max)), slack_(kSlackInRMin * r_min) {
  size_t inside = 0;
  for (const Vec2& p : points) inside += covered_.Contains(p) ? 1 : 0;
  const double side = covered_.Width();
  const double area = side * side;
  cell_ = std::clamp(
      std::sqrt(kPointsPerCell * area / static_cast<double>(std::max<size_t>(inside, 1))), r_min,
      2 * r_max);
  inverse_cell_ = 1.0 / cell_;
  // One cell more than the square needs: the last cell's far edge then lies beyond the
  // square's whatever the rounding of side / cell.
  side_ = static_cast<int>(std::ceil(side * inverse_cell_)) + 1;
  const auto cells = static_cast<size_t>(side_) * static_cast<size_t>(side_);
  std::vector<uint32_t> cell_of(points.size(), std::numeric_limits<uint32_t>::max());
  std::vector<uint32_t> counts(cells + 1, 0);
  for (size_t k = 0; k < points.size(); ++k) {
    if (!covered_.Contains(points[k])) continue;
    const double gx = (points[k].x - covered_.x0) * inverse_cell_;
    const double gy = (points[k].y - covered_.y0) * inverse_cell_;
    const int cx = std::min(static_cast<int>(gx), side_ - 1);
    const int cy = std::min(static_cast<int>(gy), side_ - 1);
    cell_of[k] = static_cast<uint32_t>(cy * side_ + cx);
    ++counts[cell_of[k] + 1];
  }
  for (size_t c = 0; c < cells; ++c) counts[c + 1] += counts[c];
  cell_start_ = counts;
  points_.resize(cell_start_.back());
  ids_.resize(cell_start_.back());
  // Stable within a cell (input order), so a grid is a pure function of its input.
  for (size_t k = 0; k < points.size(); ++k) {
    if (cell_of[k] == std::numeric_limits<uint32_t>::max()) continue;
    const uint32_t slot = counts[cell_of[k]]++;
    points_[slot] = points[k];
    ids_[slot] = ids[k];
  }
}

size_t FieldNearestGrid::Bytes() const {
  return sizeof(*this) + cell_start_.capacity() * sizeof(uint32_t) +
         points_.capacity() * sizeof(Vec2) + ids_.capacity() * sizeof(uint64_t);
}

void FieldNearestGrid::ScanRow(int row, int first, int last, const Vec2& p,
                               TwoNearest& best) const {
  const uint32_t end = cell_start_[static_cast<size_t>(row) * side_ + last + 1];
  for (uint32_t k = cell_start_[static_cast<size_t>(row) * side_ + first]; k < end; ++k) {
    OfferCandidate(SquaredDistanceFrom(p, points_[k]), ids_[k], points_[k], best);
  }
}

bool FieldNearestGrid::FindTwoNearest(const Vec2& p, TwoNearest& best) const {
  const double gx = (p.x - covered_.x0) * inverse_cell_;
  const double gy = (p.y - covered_.y0) * inverse_cell_;
  if (!(gx >= 0 && gx < side_ && gy >= 0 && gy < side_)) return false;  // NaN too
  const int cx = static_cast<int>(gx), cy = static_cast<int>(gy);
  // Every world point nearer than `edge` lies inside the covered square, hence in the grid.
  const double edge =
      std::min({p.x - covered_.x0, covered_.x1 - p.x, p.y - covered_.y0, covered_.y1 - p.y}) -
      slack_;
  best = TwoNearest{};
  constexpr double kUnbounded = std::numeric_limits<double>::infinity();
  for (int ring = 0;; ++ring) {
    const int x_lo = cx - ring, x_hi = cx + ring, y_lo = cy - ring, y_hi = cy + ring;
    const int scan_x_lo = std::max(x_lo, 0), scan_x_hi = std::min(x_hi, side_ - 1);
    // The ring: its bottom and top rows whole, its side columns between them.
    for (int row = std::max(y_lo, 0); row <= std::min(y_hi, side_ - 1); ++row) {
      if (row == y_lo || row == y_hi) {
        ScanRow(row, scan_x_lo, scan_x_hi, p, best);
        continue;
      }
      if (x_lo >= 0) ScanRow(row, x_lo, x_lo, p, best);
      if (x_hi < side_) ScanRow(row, x_hi, x_hi, p, best);
    }
    // Radius the cells examined surely cover: the distance from p to the block's nearest
    // edge. A side clipped at the grid's edge bounds nothing: no point lies beyond it, and
    // `edge` covers the square's own limit.
    const double block =
        std::min({x_lo >= 0 ? gx - x_lo : kUnbounded, x_hi < side_ ? x_hi + 1 - gx : kUnbounded,
                  y_lo >= 0 ? gy - y_lo : kUnbounded, y_hi < side_ ? y_hi + 1 - gy : kUnbounded}) *
            cell_ -
        slack_;
    const double covered = std::min(block, edge);
    if (covered >= 0 && best.squared2 <= covered * covered) return true;
    // More rings cannot cover past the square's edge.
    if (block >= edge) return false;
  }
}

}  // namespace scallop
