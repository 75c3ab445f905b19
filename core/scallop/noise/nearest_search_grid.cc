// NearestSearchGrid: bucketing by counting sort, and the two-phase search
// (p's 3x3 block of cells, then the cells the second distance still reaches).
#include "scallop/noise/nearest_search_grid.h"

#include <algorithm>
#include <cmath>

namespace scallop {
namespace {

constexpr int kSide = NearestSearchGrid::kCellsPerSide;

// Rounding in a cell coordinate (x - origin) / d is below 2^-20 cells within
// the precision range (one ulp of 2^32 d is at most 2^-20 d); 2^-12 d leaves
// a wide margin and costs nothing measurable (docs/noise.md, "Rounding").
constexpr double kSlackInD = 0x1.0p-12;

// When fewer than two points lie in p's 3x3 block, search to this radius,
// the maximality bound F2 < 2 d (1 + tolerance) with tolerance << 1%.
constexpr double kSecondBoundInD = 2.01;

}  // namespace

Rect NearestSearchGrid::CoveredSquare(double min_distance, RegionKey key) {
  const Rect region = RegionLayout(min_distance).RegionRect(key);
  const double margin = kMarginCells * min_distance;
  return {region.x0 - margin, region.y0 - margin, region.x1 + margin, region.y1 + margin};
}

NearestSearchGrid::NearestSearchGrid(double min_distance, RegionKey key,
                                     std::span<const Vec2> points, std::span<const uint64_t> ids)
    : key_(key),
      cell_(min_distance),
      inverse_cell_(1.0 / min_distance),
      slack_(kSlackInD * min_distance) {
  const Rect region = RegionLayout(min_distance).RegionRect(key);
  origin_ = {region.x0 - kMarginCells * min_distance, region.y0 - kMarginCells * min_distance};
  // Counting sort by cell, row-major. -1 marks a point outside the grid.
  std::vector<int> cell_of(points.size(), -1);
  std::vector<uint32_t> counts(kSide * kSide + 1, 0);
  for (size_t k = 0; k < points.size(); ++k) {
    const double gx = (points[k].x - origin_.x) * inverse_cell_;
    const double gy = (points[k].y - origin_.y) * inverse_cell_;
    if (!(gx >= 0 && gx < kSide && gy >= 0 && gy < kSide)) continue;
    cell_of[k] = static_cast<int>(gy) * kSide + static_cast<int>(gx);
    ++counts[cell_of[k] + 1];
  }
  cell_start_.resize(kSide * kSide + 1);
  for (int c = 0; c < kSide * kSide; ++c) counts[c + 1] += counts[c];
  std::copy(counts.begin(), counts.end(), cell_start_.begin());
  points_.resize(cell_start_.back());
  ids_.resize(cell_start_.back());
  // Stable within a cell (input order), so a grid is a pure function of its input.
  for (size_t k = 0; k < points.size(); ++k) {
    if (cell_of[k] < 0) continue;
    const uint32_t slot = counts[cell_of[k]]++;
    points_[slot] = points[k];
    ids_[slot] = ids[k];
  }
}

size_t NearestSearchGrid::Bytes() const {
  return sizeof(*this) + cell_start_.capacity() * sizeof(uint32_t) +
         points_.capacity() * sizeof(Vec2) + ids_.capacity() * sizeof(uint64_t);
}

void NearestSearchGrid::ScanRow(int row, int first, int last, Vec2 p, TwoNearest& best) const {
  const uint32_t end = cell_start_[row * kSide + last + 1];
  for (uint32_t k = cell_start_[row * kSide + first]; k < end; ++k) {
    OfferCandidate(SquaredDistanceFrom(p, points_[k]), ids_[k], points_[k], best);
  }
}

bool NearestSearchGrid::FindTwoNearest(Vec2 p, TwoNearest& best) const {
  best = TwoNearest{};
  const double gx = (p.x - origin_.x) * inverse_cell_;
  const double gy = (p.y - origin_.y) * inverse_cell_;
  // p's 3x3 block must lie in the grid (this also rejects NaN).
  if (!(gx >= 1 && gx < kSide - 1 && gy >= 1 && gy < kSide - 1)) return false;
  const int cx = static_cast<int>(gx), cy = static_cast<int>(gy);  // floor: both >= 1
  // The radius about p that cells [x_lo, x_hi] x [y_lo, y_hi] surely cover,
  // less the rounding slack: every point nearer than this was examined.
  auto covered = [&](int x_lo, int x_hi, int y_lo, int y_hi) {
    return std::min({gx - x_lo, x_hi + 1 - gx, gy - y_lo, y_hi + 1 - gy}) * cell_ - slack_;
  };

  // Phase 1: p's cell and its 8 neighbours hold F1 and F2 most of the time.
  for (int row = cy - 1; row <= cy + 1; ++row) ScanRow(row, cx - 1, cx + 1, p, best);
  const double radius1 = covered(cx - 1, cx + 1, cy - 1, cy + 1);
  if (best.squared2 <= radius1 * radius1) return true;

  // Phase 2: every cell that may hold a point nearer than the second so far
  // (or, with fewer than two, nearer than the maximality bound).
  const double reach =
      std::isfinite(best.squared2) ? std::sqrt(best.squared2) : kSecondBoundInD * cell_;
  const double reach_cells = reach * inverse_cell_ + 2 * kSlackInD;
  if (!(reach_cells < kSide)) return false;
  const int x_lo = std::min(cx - 1, static_cast<int>(std::floor(gx - reach_cells)));
  const int x_hi = std::max(cx + 1, static_cast<int>(std::floor(gx + reach_cells)));
  const int y_lo = std::min(cy - 1, static_cast<int>(std::floor(gy - reach_cells)));
  const int y_hi = std::max(cy + 1, static_cast<int>(std::floor(gy + reach_cells)));
  if (x_lo < 0 || y_lo < 0 || x_hi >= kSide || y_hi >= kSide) return false;
  for (int row = y_lo; row <= y_hi; ++row) {
    if (row < cy - 1 || row > cy + 1) {
      ScanRow(row, x_lo, x_hi, p, best);
      continue;
    }
    // The 3x3 block was scanned in phase 1: a second visit would count its
    // points twice.
    if (x_lo <= cx - 2) ScanRow(row, x_lo, cx - 2, p, best);
    if (cx + 2 <= x_hi) ScanRow(row, cx + 2, x_hi, p, best);
  }
  const double radius2 = covered(x_lo, x_hi, y_lo, y_hi);
  return best.squared2 <= radius2 * radius2;
}

}  // namespace scallop
