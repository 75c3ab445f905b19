// BoundaryGrid: A3's neighbour grid on a rectangle. Cells as PointGrid's
// (a point alone in each), but laid out for A3's one query, the 7 x 7 cells
// around a candidate: a bit per cell says which hold a point, so the query
// reads only those (at most 2 in 5); positions only, 16 bytes a cell instead
// of 24, in tiles of 8 x 8 cells, so that it touches at most 4 tiles (at 1M
// points a PointGrid row is about 10 pages, and the query touched 7 of them).
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <vector>

#if __has_include(<sys/mman.h>)
#include <sys/mman.h>
#endif

#include "scallop/geometry/rect.h"
#include "scallop/geometry/vec2.h"

namespace scallop {

// Allocates large arrays (4 MiB and more) aligned to 2 MiB and asks Linux to
// back them with huge pages: at 1M points BoundaryGrid's positions span
// 40 MB, and with 4 KiB pages a query's rows cost TLB misses and each
// page's first touch a fault (kernel time was 8% of a 1M run in perf).
template <typename T>
struct HugePageAllocator {
  using value_type = T;
  static constexpr size_t kHuge = size_t{2} << 20;
  HugePageAllocator() = default;
  template <typename U>
  explicit HugePageAllocator(const HugePageAllocator<U>&) {}
  static bool Large(size_t n) { return n >= 2 * kHuge / sizeof(T); }
  // Through the aligned operator new, so that whatever counts the heap (the
  // benchmarks' bytes per point) sees these bytes too.
  T* allocate(size_t n) {
    if (!Large(n)) return std::allocator<T>().allocate(n);
    if (n > (SIZE_MAX - kHuge) / sizeof(T)) throw std::bad_alloc();
    const size_t bytes = (n * sizeof(T) + kHuge - 1) / kHuge * kHuge;
    void* p = ::operator new (bytes, std::align_val_t{kHuge});
#ifdef MADV_HUGEPAGE
    madvise(p, bytes, MADV_HUGEPAGE);  // advice only: its failure changes nothing
#endif
    return static_cast<T*>(p);
  }
  void deallocate(T* p, size_t n) {
    if (!Large(n)) return std::allocator<T>().deallocate(p, n);
    ::operator delete (p, std::align_val_t{kHuge});
  }
  friend bool operator==(const HugePageAllocator&, const HugePageAllocator&) { return true; }
};

class BoundaryGrid {
 public:
  // Covers `area` grown by `margin` on every side. REQUIRES: min_distance > 0.
  BoundaryGrid(const Rect& area, double min_distance, double margin) {
    Reset(area, min_distance, margin);
  }

  // Makes this grid what BoundaryGrid(area, min_distance, margin) would be,
  // empty, keeping its memory where that suffices: a plane region's run
  // reuses the grid of the run before it (BoundaryScratch). O(cells / 8).
  void Reset(const Rect& area, double min_distance, double margin) {
    origin_ = {area.x0 - margin, area.y0 - margin};
    const double width = area.Width() + 2 * margin, height = area.Height() + 2 * margin;
    // A diagonal a millionth short of min_distance, so that no two stored
    // points share a cell even though cells are found by a product, which
    // can be a few ulps off (see TruncatedColumnOf).
    cell_size_ = min_distance / std::sqrt(2.0) * (1.0 - 1e-6);
    cells_per_unit_ = 1.0 / cell_size_;
    columns_ = static_cast<int64_t>(std::floor(width / cell_size_)) + 1;
    rows_ = static_cast<int64_t>(std::floor(height / cell_size_)) + 1;
    tile_columns_ = (columns_ + kTile - 1) / kTile;
    const int64_t tile_rows = (rows_ + kTile - 1) / kTile;
    // Left uninitialised: only occupied cells are read. Filling them (about
    // 50 kB for a plane region) was 3% of a cold tile's time.
    const auto cells = static_cast<size_t>(tile_columns_ * tile_rows * kTile * kTile);
    if (!positions_ || positions_.get_deleter().cells < cells) {
      positions_.reset();
      positions_ = {HugePageAllocator<Vec2>().allocate(cells), PositionsDeleter{cells}};
    }
    // 8 spare bytes a row: OccupancyFrom reads 8 bytes from any column's
    // byte; kTile - 1 spare rows: GatherNear reads 8 rows from any row.
    occupancy_stride_ = (columns_ + 7) / 8 + 8;
    occupancy_.assign(static_cast<size_t>((rows_ + kTile - 1) * occupancy_stride_), 0);
    // For a block whose first row (column) is at `first` in its tile: where
    // its k-th row (column) starts, in cells from the block's first cell.
    const auto tile_row_cells = static_cast<size_t>(tile_columns_ * kTile * kTile);
    for (size_t first = 0; first < kTile; ++first) {
      for (size_t k = 0; k < kTile; ++k) {
        const size_t at = first + k;
        row_offsets_[first][k] = (at / kTile) * tile_row_cells + (at % kTile) * kTile;
        column_offsets_[first][k] = (at / kTile) * kTile * kTile + at % kTile;
      }
    }
  }

  // As PointGrid::Insert, but only the position is kept. REQUIRES: p within
  // the covered area and no point closer than min_distance already stored
  // (so every stored point is alone in its cell, and it is the only point there).
  void Insert(int32_t /*index*/, Vec2 p) {
    // Inside the covered area the products are not negative, so truncation
    // is floor (which, without SSE4.1, is a libm call per coordinate).
    const int64_t column = TruncatedColumnOf(p.x), row = TruncatedRowOf(p.y);
    positions_[CellIndex(column, row)] = p;
    occupancy_[static_cast<size_t>(row * occupancy_stride_ + column / 8)] |=
        static_cast<uint8_t>(1u << (column % 8));
  }

  // The positions PointGrid::GatherNear gives on a rectangle, in row-major
  // order of this grid's cells: those of the stored points other than point
  // `self` with SquaredLength(q - p) < limit_squared, among the cells within
  // `radius` of p.
  // REQUIRES: self < 0 (no point excluded), or p is the position of stored
  // point self. O((radius / cell)^2); when the query spans at most 8 x 8
  // cells (A3's 7 x 7), it reads only the occupied ones, whose bits it
  // gathers first, and has no branch per cell.
  size_t GatherNear(Vec2 p, double radius, double limit_squared, int32_t self,
                    std::vector<Vec2>& out) const {
    // Truncation is floor here: negatives are clamped to 0 either way.
    const int64_t c0 = std::max<int64_t>(TruncatedColumnOf(p.x - radius), 0);
    const int64_t c1 = std::min<int64_t>(TruncatedColumnOf(p.x + radius), columns_ - 1);
    const int64_t r0 = std::max<int64_t>(TruncatedRowOf(p.y - radius), 0);
    const int64_t r1 = std::min<int64_t>(TruncatedRowOf(p.y + radius), rows_ - 1);
    if (c0 > c1 || r0 > r1) return 0;
    const auto most = static_cast<size_t>((r1 - r0 + 1) * (c1 - c0 + 1));
    if (out.size() < most) out.resize(most);
    // Point `self` is alone in p's own cell (Insert's REQUIRES).
    const int64_t own_column = std::clamp<int64_t>(TruncatedColumnOf(p.x), 0, columns_ - 1);
    const int64_t own_row = std::clamp<int64_t>(TruncatedRowOf(p.y), 0, rows_ - 1);
    if (c1 - c0 >= kTile || r1 - r0 >= kTile) {
      return GatherWide(p, limit_squared, self >= 0, c0, c1, r0, r1, own_column, own_row, out);
    }
    size_t kept = 0;
    // Bit 8 k + j: the cell of row r0 + k, column c0 + j, occupied. Ascending
    // bits are row-major order. Always 8 rows, those past r1 masked off (the
    // occupancy has spare rows of zeros): a fixed count, where a count of 6
    // or 7 cost a mispredicted branch now and then.
    const uint64_t row_mask = (uint64_t{2} << (c1 - c0)) - 1;
    uint64_t occupied = 0;
    for (int64_t k = 0; k < kTile; ++k) {
      const uint64_t in_window = -static_cast<uint64_t>(k <= r1 - r0);
      occupied |= (OccupancyFrom(c0, r0 + k) & row_mask & in_window) << (8 * k);
    }
    if (self >= 0) occupied &= ~(uint64_t{1} << (8 * (own_row - r0) + (own_column - c0)));
    // Where the block's row k and column j start, as cell offsets from cell
    // (c0, r0), looked up per occupied cell: fewer instructions a cell than
    // working out its tile.
    const size_t* row_offsets = row_offsets_[r0 % kTile];
    const size_t* column_offsets = column_offsets_[c0 % kTile];
    const Vec2* block = &positions_[CellIndex(c0 - c0 % kTile, r0 - r0 % kTile)];
    while (occupied != 0) {
      const int bit = std::countr_zero(occupied);
      occupied &= occupied - 1;
      const size_t offset = row_offsets[bit >> 3] + column_offsets[bit & 7];
      const Vec2 q = block[offset];
      out[kept] = q;
      kept += SquaredLength(q - p) < limit_squared;
    }
    return kept;
  }

  Vec2 NearestImage(Vec2, Vec2 q) const { return q; }
  Vec2 WrapIntoDomain(Vec2 p) const { return p; }

 private:
  static constexpr int64_t kTile = 8;  // cells a side of a tile: 8 x 8 x 16 bytes = 1 KiB

  // Frees positions_, which is allocated without constructing its cells.
  struct PositionsDeleter {
    size_t cells;
    void operator()(Vec2* positions) const {
      HugePageAllocator<Vec2>().deallocate(positions, cells);
    }
  };

  // GatherNear for a query wider than 8 cells, which A3 never makes: every
  // cell of columns c0..c1, rows r0..r1, but the own cell if `exclude_own`.
  // Out of line, so that the narrow path stays small enough to inline.
  [[gnu::noinline]] size_t GatherWide(Vec2 p, double limit_squared, bool exclude_own, int64_t c0,
                                      int64_t c1, int64_t r0, int64_t r1, int64_t own_column,
                                      int64_t own_row, std::vector<Vec2>& out) const {
    size_t kept = 0;
    for (int64_t r = r0; r <= r1; ++r) {
      for (int64_t c = c0; c <= c1; ++c) {
        if (!Occupied(c, r) || (exclude_own && c == own_column && r == own_row)) continue;
        const Vec2 q = positions_[CellIndex(c, r)];
        out[kept] = q;
        kept += SquaredLength(q - p) < limit_squared;
      }
    }
    return kept;
  }

  bool Occupied(int64_t c, int64_t r) const {
    return (occupancy_[static_cast<size_t>(r * occupancy_stride_ + c / 8)] >> (c % 8)) & 1;
  }

  // Row r's occupancy bits from column c on (bit j: column c + j), at least 56 of them.
  uint64_t OccupancyFrom(int64_t c, int64_t r) const {
    uint64_t word;
    std::memcpy(&word, &occupancy_[static_cast<size_t>(r * occupancy_stride_ + c / 8)], 8);
    return word >> (c % 8);  // little-endian: byte k holds columns 8 k to 8 k + 7
  }

  // The column and row of a coordinate, where its offset from the origin is
  // not negative; towards zero otherwise. By a product with 1 / cell size,
  // not a quotient: there are
  // eight a point, and a division's latency stood at the head of every
  // query. A point within a few ulps of a cell's bound may so be filed one
  // cell over, which is harmless: rounding is monotone, so a query's cells
  // still hold every point within its radius, and a cell still holds one
  // point at most (it would take an error of 3.5e-7 d, where the product's
  // is below 4e-16 times the column, and a grid has far fewer than 10^9).
  int64_t TruncatedColumnOf(double x) const {
    return static_cast<int64_t>((x - origin_.x) * cells_per_unit_);
  }
  int64_t TruncatedRowOf(double y) const {
    return static_cast<int64_t>((y - origin_.y) * cells_per_unit_);
  }
  // REQUIRES: column, row >= 0 (unsigned, so / and % are shifts and masks:
  // this runs for every neighbour of every candidate).
  size_t CellIndex(int64_t column, int64_t row) const {
    const auto c = static_cast<uint64_t>(column), r = static_cast<uint64_t>(row);
    constexpr auto kSide = static_cast<uint64_t>(kTile);
    const uint64_t tile = (r / kSide) * static_cast<uint64_t>(tile_columns_) + c / kSide;
    return static_cast<size_t>(tile * kSide * kSide + (r % kSide) * kSide + c % kSide);
  }

  Vec2 origin_;
  double cell_size_, cells_per_unit_;
  int64_t columns_, rows_, tile_columns_;
  // Tiled cells; a cell's position is set (and read) only where occupancy_ says so.
  std::unique_ptr<Vec2[], PositionsDeleter> positions_;
  size_t row_offsets_[kTile][kTile], column_offsets_[kTile][kTile];  // see Reset
  int64_t occupancy_stride_;                                         // bytes a row
  std::vector<uint8_t> occupancy_;  // a bit per cell, row-major: which cells hold a point
};

}  // namespace scallop
