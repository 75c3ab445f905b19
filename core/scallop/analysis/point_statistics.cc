// Normalised radius and pair distance histogram (see point_statistics.h):
// a counting-sorted uniform grid finds the pairs within reach.
#include "scallop/analysis/point_statistics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

namespace scallop {
namespace {

constexpr int kMaxBins = 10'000'000;

// Distinct cells c - 1, c, c + 1 along one axis (wrapped on a torus); fewer
// than three when a torus has fewer than three cells, so no pair counts twice.
int NeighbourCells(int64_t cell, int64_t cells, bool torus, int64_t out[3]) {
  int count = 0;
  for (int64_t offset = -1; offset <= 1; ++offset) {
    int64_t c = cell + offset;
    if (torus) {
      c = ((c % cells) + cells) % cells;
    } else if (c < 0 || c >= cells) {
      continue;
    }
    if (std::find(out, out + count, c) == out + count) out[count++] = c;
  }
  return count;
}

// Integral of a W x H rectangle's set covariance (W - |dx|)(H - |dy|) over the
// disk of radius r: the number of ordered pairs of uniform points closer than r,
// times (W H)^2. Valid for r <= min(W, H).
double CovarianceWithin(double r, double width, double height) {
  return std::numbers::pi * width * height * r * r - 4.0 / 3.0 * (width + height) * r * r * r +
         0.5 * r * r * r * r;
}

}  // namespace

StatusOr<double> NormalisedRadius(int64_t point_count, double area, double min_distance) {
  if (point_count <= 0) {
    return InvalidArgument("point_count: must be > 0, got " + std::to_string(point_count));
  }
  if (!std::isfinite(area) || !(area > 0.0)) {
    return InvalidArgument("area: must be finite and > 0");
  }
  if (!std::isfinite(min_distance) || !(min_distance > 0.0)) {
    return InvalidArgument("min_distance: must be finite and > 0");
  }
  const double density = static_cast<double>(point_count) / area;
  const double max_spacing = std::sqrt(2.0 / (std::numbers::sqrt3 * density));
  return min_distance / max_spacing;
}

StatusOr<PairDistanceHistogram> HistogramPairDistances(std::span<const Vec2> points,
                                                       const Domain& domain, double max_distance,
                                                       int bin_count) {
  const Rect& rect = domain.rect;
  if (!std::isfinite(rect.x0) || !std::isfinite(rect.y0) || !std::isfinite(rect.x1) ||
      !std::isfinite(rect.y1) || !(rect.x0 < rect.x1) || !(rect.y0 < rect.y1)) {
    return InvalidArgument("domain.rect: must be finite with x0 < x1 and y0 < y1");
  }
  const double width = rect.Width(), height = rect.Height();
  const double reach = domain.torus ? 0.5 * std::min(width, height) : std::min(width, height);
  if (!std::isfinite(max_distance) || !(max_distance > 0.0) || max_distance > reach) {
    return InvalidArgument("max_distance: must be in (0, " + std::to_string(reach) + "] (min side" +
                           (domain.torus ? " / 2 on a torus)" : ")"));
  }
  if (bin_count < 1 || bin_count > kMaxBins) {
    return InvalidArgument("bin_count: must be in [1, " + std::to_string(kMaxBins) + "]");
  }
  if (points.size() > std::numeric_limits<uint32_t>::max()) {
    return InvalidArgument("points: at most 2^32 - 1");
  }
  for (size_t i = 0; i < points.size(); ++i) {
    if (!rect.Contains(points[i])) {
      return InvalidArgument("points[" + std::to_string(i) +
                             "]: must be finite and inside the half-open domain.rect");
    }
  }

  // Cells at least max_distance wide, so every pair within reach is in
  // neighbouring cells; no more cells than about 4 N, so a tiny reach does not
  // allocate a huge empty grid.
  const double cap = std::max(1.0, std::ceil(2.0 * std::sqrt(static_cast<double>(points.size()))));
  const auto cells_along = [&](double side) {
    return static_cast<int64_t>(std::clamp(std::floor(side / max_distance), 1.0, cap));
  };
  const int64_t columns = cells_along(width), rows = cells_along(height);
  const double cell_width = width / static_cast<double>(columns);
  const double cell_height = height / static_cast<double>(rows);
  const auto cell_of = [&](Vec2 p) {
    const int64_t column = std::clamp<int64_t>(
        static_cast<int64_t>(std::floor((p.x - rect.x0) / cell_width)), 0, columns - 1);
    const int64_t row = std::clamp<int64_t>(
        static_cast<int64_t>(std::floor((p.y - rect.y0) / cell_height)), 0, rows - 1);
    return row * columns + column;
  };

  // Counting sort of point indices by cell.
  std::vector<int64_t> cell_start(static_cast<size_t>(columns * rows + 1), 0);
  std::vector<int64_t> cell_of_point(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    cell_of_point[i] = cell_of(points[i]);
    ++cell_start[static_cast<size_t>(cell_of_point[i]) + 1];
  }
  for (size_t c = 1; c < cell_start.size(); ++c) cell_start[c] += cell_start[c - 1];
  std::vector<int64_t> fill(cell_start.begin(), cell_start.end() - 1);
  std::vector<uint32_t> by_cell(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    by_cell[static_cast<size_t>(fill[static_cast<size_t>(cell_of_point[i])]++)] =
        static_cast<uint32_t>(i);
  }

  PairDistanceHistogram histogram;
  histogram.max_distance = max_distance;
  histogram.bin_width = max_distance / bin_count;
  histogram.pair_counts.assign(static_cast<size_t>(bin_count), 0);
  const double squared_reach = max_distance * max_distance;

  for (size_t i = 0; i < points.size(); ++i) {
    const Vec2 a = points[i];
    const int64_t column = cell_of_point[i] % columns, row = cell_of_point[i] / columns;
    int64_t neighbour_columns[3], neighbour_rows[3];
    const int column_count = NeighbourCells(column, columns, domain.torus, neighbour_columns);
    const int row_count = NeighbourCells(row, rows, domain.torus, neighbour_rows);
    for (int r = 0; r < row_count; ++r) {
      for (int c = 0; c < column_count; ++c) {
        const size_t cell = static_cast<size_t>(neighbour_rows[r] * columns + neighbour_columns[c]);
        for (int64_t k = cell_start[cell]; k < cell_start[cell + 1]; ++k) {
          const uint32_t j = by_cell[static_cast<size_t>(k)];
          // Each unordered pair is met from both ends; count it from the lower index.
          if (j <= i) continue;
          double dx = a.x - points[j].x, dy = a.y - points[j].y;
          if (domain.torus) {
            dx -= width * std::round(dx / width);
            dy -= height * std::round(dy / height);
          }
          const double squared = dx * dx + dy * dy;
          if (squared >= squared_reach) continue;
          const int bin =
              std::min(static_cast<int>(std::sqrt(squared) / histogram.bin_width), bin_count - 1);
          ++histogram.pair_counts[static_cast<size_t>(bin)];
        }
      }
    }
  }

  const double n = static_cast<double>(points.size());
  const double pairs = 0.5 * n * (n - 1.0);
  histogram.radial_distribution.assign(static_cast<size_t>(bin_count), 0.0);
  for (int k = 0; k < bin_count; ++k) {
    const double r0 = k * histogram.bin_width, r1 = (k + 1) * histogram.bin_width;
    const double fraction =
        domain.torus ? std::numbers::pi * (r1 * r1 - r0 * r0) / (width * height)
                     : (CovarianceWithin(r1, width, height) - CovarianceWithin(r0, width, height)) /
                           (width * width * height * height);
    const double expected = pairs * fraction;
    if (expected > 0.0) {
      histogram.radial_distribution[static_cast<size_t>(k)] =
          static_cast<double>(histogram.pair_counts[static_cast<size_t>(k)]) / expected;
    }
  }
  return histogram;
}

}  // namespace scallop
