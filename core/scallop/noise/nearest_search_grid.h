// NearestSearchGrid: one region's points plus a 3 d margin of its
// neighbours', bucketed into cells of side d, for finding the two nearest
// points of a position with a search that certifies its own answer.
// See docs/noise.md for the argument.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "scallop/geometry/rect.h"
#include "scallop/geometry/vec2.h"
#include "scallop/noise/cell_value.h"
#include "scallop/noise/nearest_point.h"
#include "scallop/plane/region_layout.h"

namespace scallop {

// The two nearest points of a position, ordered by (squared distance, id):
// distances are compared as dx*dx + dy*dy computed in doubles (dx = p.x - q.x),
// and equal ones by the smaller id. Indices point into the searched set.
struct TwoNearest {
  double squared1 = std::numeric_limits<double>::infinity();
  double squared2 = std::numeric_limits<double>::infinity();
  uint64_t id1 = 0;
  uint64_t id2 = 0;
  Vec2 point1;
  Vec2 point2;
};

// The basis from the two nearest: f1 and f2 their distances, correctly rounded.
inline NearestPoint ToNearestPoint(const TwoNearest& best) {
  return {.id = best.id1,
          .position = best.point1,
          .f1 = std::sqrt(best.squared1),
          .f2 = std::sqrt(best.squared2),
          .second_id = best.id2,
          .cell_value = CellValue(best.id1)};
}

// A position of a batch and the slot of its answer (NearestSearchGrid::AnswerEach).
struct IndexedPosition {
  Vec2 position;
  uint32_t index;  // into the batch's results
};

// (dx*dx + dy*dy) for p and q, the one expression every search and oracle uses.
inline double SquaredDistanceFrom(Vec2 p, Vec2 q) {
  const double dx = p.x - q.x, dy = p.y - q.y;
  return dx * dx + dy * dy;
}

// Offers point q (id) to `best`, keeping the two smallest by (squared, id).
inline void OfferCandidate(double squared, uint64_t id, Vec2 q, TwoNearest& best) {
  if (squared > best.squared2 || (squared == best.squared2 && id >= best.id2)) return;
  if (squared < best.squared1 || (squared == best.squared1 && id < best.id1)) {
    best.squared2 = best.squared1;
    best.id2 = best.id1;
    best.point2 = best.point1;
    best.squared1 = squared;
    best.id1 = id;
    best.point1 = q;
  } else {
    best.squared2 = squared;
    best.id2 = id;
    best.point2 = q;
  }
}

// A point of a search grid with what an answer copies from it, in one
// record: the two points a quick pass finds are then two lines at most (the
// coordinates and ids in arrays of their own were up to six). The cell value
// is stored: hashing the id for every answer cost about 5% of a lookup.
struct alignas(32) SearchGridPoint {
  Vec2 position;
  uint64_t id = 0;
  double cell_value = 0;  // CellValue(id)
};

class NearestSearchGrid {
 public:
  // The vector width of the search's first pass. Both widths give the same
  // answers to the bit; kWidest takes four lanes (AVX2) where the CPU has
  // them, else two (SSE2). The tests run each.
  enum class FirstPassWidth { kWidest, kTwoLanes };

  // Cells of margin on each side of the region: F2 < 2 d (1 + tolerance) on
  // a maximal set, and a position in the region is at most 1 cell from the
  // margin's inner edge, so 3 cells always hold the answer (docs/noise.md).
  static constexpr int kMarginCells = 3;
  static constexpr int kCellsPerSide = static_cast<int>(kRegionSideInD) + 2 * kMarginCells;

  // The square the grid's cells cover: region `key` grown by 3 d on each side
  // (approximately: cell membership is decided by Cell() below).
  static Rect CoveredSquare(double min_distance, RegionKey key);

  // Buckets the points of `points` (ids[k] is the id of points[k]) whose cell
  // falls in the grid; the others are ignored. For the search to be exact
  // `points` must hold every point of the world in CoveredSquare grown by
  // 1 d (so rounding at the edges cannot lose one). REQUIRES: min_distance
  // valid (world.h), ids.size() == points.size(), ids distinct.
  // Cost: O(points); about 19 KB for an A3 region.
  NearestSearchGrid(double min_distance, RegionKey key, std::span<const Vec2> points,
                    std::span<const uint64_t> ids, FirstPassWidth width = FirstPassWidth::kWidest);

  // Whether this CPU runs the four-lane first pass (x86 with AVX2).
  static bool FourLanesAvailable();
  // The lanes this grid's first pass uses: 2 or 4.
  int FirstPassLanes() const { return four_lanes_ ? 4 : 2; }

  // The two nearest of the grid's points to p, in `best`. Returns true only
  // when the answer is certified: every point within the second distance of p
  // was examined, so no point the grid holds and none it does not (if
  // `points` was complete) can be nearer. Returns false, leaving `best`
  // unspecified, when the answer would need cells beyond the grid (p far
  // outside the region, or fewer than 2 points within about 2 d).
  // Cost: 12 keys without data-dependent branches (p's 3x3 block of cells,
  // about 8 points, docs/noise.md) when F2 is within that block and no two
  // distances tie, else the exact scan of up to 49 cells (for 1% of positions
  // in A3 worlds, 5% in A1 and A2).
  // Thread-safe (const).
  // p by reference: passed by value in two registers, GCC 12 rebuilt it
  // through the stack, a store-forwarding stall that cost more than the scan.
  bool FindTwoNearest(const Vec2& p, TwoNearest& best) const;

  // FindTwoNearest of each entry, its answer (ToNearestPoint) written to
  // results[entry.index] when certified; the offsets in `positions` of the
  // entries it cannot certify are appended to `refused`, their results left
  // alone. The same answers to the bit as FindTwoNearest, and faster than a
  // call of it a position: one call for a batch keeps the search's constants
  // in registers, a pair of positions shares one vector of float keys, and
  // two pairs run side by side, two independent chains of loads and
  // compares (docs/noise.md, "The paired pass", "Answering a batch").
  // `next`, if not null, is the grid the caller answers from next: its
  // lines are prefetched into L2 a few at a time meanwhile, since a batch's
  // grids (19 KB each, a few hundred) do not stay in L2 from one batch to
  // the next. A hint: the answers do not depend on it.
  // REQUIRES: every entry's index < results.size().
  void AnswerEach(std::span<const IndexedPosition> positions, std::span<NearestPoint> results,
                  std::vector<uint32_t>& refused, const NearestSearchGrid* next = nullptr) const;

  RegionKey key() const { return key_; }
  size_t PointCount() const { return cell_start_.back(); }
  // Bytes held, for the lookup cache's budget.
  size_t Bytes() const;

 private:
  // Examines the points of cells [first, last] of one row.
  void ScanRow(int row, int first, int last, const Vec2& p, TwoNearest& best) const;
  // The radius about p (at cell coordinates gx, gy) that cells [x_lo, x_hi] x
  // [y_lo, y_hi] surely cover, less the rounding slack: every point nearer
  // than this is in those cells.
  double Covered(double gx, double gy, int x_lo, int x_hi, int y_lo, int y_hi) const;
  // Phases 1 and 2 with OfferCandidate: exact whatever the ties.
  bool FindTwoNearestExactly(const Vec2& p, double gx, double gy, TwoNearest& best) const;
  // One position's phase 1: p's cell (row-major index) and the radius its block covers.
  struct BlockQuery {
    const Vec2* p;
    TwoNearest* best;
    int cell = 0;
    double radius1 = 0;
  };
  // The same for a position of a pair, whose answer goes to *out directly.
  struct PairQuery {
    const Vec2* p;
    NearestPoint* out;
    int cell = 0;
    double radius1 = 0;
  };
  // Fills the cell and radius1 (Covered, to the same bits) of the two
  // queries of a pair, all four axes in one vector; false when either's
  // block leaves the grid (BlockInGrid) or its position is NaN. g gets both
  // positions' cell coordinates (CellCoordinates) as four floats, x and y
  // of each.
  template <typename CellFloats>
  bool LocatePair(PairQuery* queries, CellFloats& g) const;
  // Phase 1 without branches on the data, kLanes double keys at a time, for
  // when its answer is certified and free of near-ties; false sends the
  // caller to the exact scan. Inlined into the entry points below (the
  // four-lane ones compiled for AVX2).
  template <int kLanes>
  bool FindInBlockQuickly(const Vec2& p, int cx, int cy, double radius1, TwoNearest& best) const;
  // A quick pass's two found, points i1 and i2 (in bounds: points or pads),
  // into *query.best with their exact squared distances; whether the second
  // lies within the radius the block covers.
  bool TakeFound(const BlockQuery& query, uint32_t i1, uint32_t i2) const;
  // The same for a pair's position whose keys were `ordered` (apart), its
  // answer (ToNearestPoint's bits) written to *query.out directly when it
  // is certified, which it returns: through a TwoNearest, the stores and
  // the reloads after cost the paired loop 3% of its instructions.
  bool StoreFound(const PairQuery& query, bool ordered, uint32_t i1, uint32_t i2) const;
  // Phase 1 for two positions at once, in float keys (kLanes of them, half
  // a position's), trusted where the three smallest of each are apart by
  // more than float rounding can blur (docs/noise.md, "The paired pass").
  // Bit q of the result: queries[q] is certified; or kAnswerEachAlone: a row
  // of a block is longer than the pass reads, so each position wants the
  // one-position pass.
  static constexpr unsigned kAnswerEachAlone = 1u << 31;
  template <int kLanes, int kPairs, typename CellFloats>
  unsigned FindPairsQuickly(const PairQuery* queries, const CellFloats* g) const;
  bool FindInBlockInTwoLanes(const Vec2& p, int cx, int cy, double radius1, TwoNearest& best) const;
  bool FindInBlockInFourLanes(const Vec2& p, int cx, int cy, double radius1,
                              TwoNearest& best) const;
  // Entries k and k + 1 of AnswerEach, through one pass of FindPairsQuickly.
  template <int kLanes>
  void AnswerPair(std::span<const IndexedPosition> positions, uint32_t k, NearestPoint* results,
                  std::vector<uint32_t>& refused) const;
  // Entries k .. k + entries - 1 after a quick pass: those whose bit
  // (bit q for entry k + q) is clear, by the exact phases.
  void Finish(std::span<const IndexedPosition> positions, uint32_t k, unsigned certified,
              uint32_t entries, NearestPoint* results, std::vector<uint32_t>& refused) const;
  // AnswerEach with kLanes lanes, inlined into the two entry points below.
  template <int kLanes>
  void AnswerEachIn(std::span<const IndexedPosition> positions, NearestPoint* results,
                    std::vector<uint32_t>& refused, const NearestSearchGrid* next) const;
  void AnswerEachInTwoLanes(std::span<const IndexedPosition> positions, NearestPoint* results,
                            std::vector<uint32_t>& refused, const NearestSearchGrid* next) const;
  void AnswerEachInFourLanes(std::span<const IndexedPosition> positions, NearestPoint* results,
                             std::vector<uint32_t>& refused, const NearestSearchGrid* next) const;
  // Walks another grid's arrays, prefetching a few lines a step (.cc).
  class LinePrefetcher;
  // AnswerEach's rare cases: entry `offset` by FindTwoNearest, or by the
  // exact phases alone once its quick pass has failed.
  void AnswerAlone(const IndexedPosition& entry, uint32_t offset, NearestPoint* results,
                   std::vector<uint32_t>& refused) const;
  void AnswerExactly(const IndexedPosition& entry, uint32_t offset, NearestPoint* results,
                     std::vector<uint32_t>& refused) const;
  // p in cell units: cell (i, j) is [i, i + 1) x [j, j + 1).
  Vec2 CellCoordinates(const Vec2& p) const {
    return {(p.x - origin_.x) * inverse_cell_, (p.y - origin_.y) * inverse_cell_};
  }
  // Whether p's 3x3 block, at cell coordinates (gx, gy), lies in the grid (false for NaN).
  static bool BlockInGrid(double gx, double gy) {
    return gx >= 1 && gx < kCellsPerSide - 1 && gy >= 1 && gy < kCellsPerSide - 1;
  }

  RegionKey key_;
  double cell_ = 0;                   // cell side, d
  double inverse_cell_ = 0;           // 1 / d, rounded
  double slack_ = 0;                  // bound on rounding in cell coordinates, in world units
  Vec2 origin_;                       // low corner of cell (0, 0)
  std::vector<uint32_t> cell_start_;  // kCellsPerSide^2 + 1 offsets into the points (row-major)
  // The points, bucketed by cell, then a few far pads (.cc).
  std::vector<SearchGridPoint> points_;
  // The same points in cell units as floats (pads far), for FindPairsQuickly.
  std::vector<float> cell_xs_, cell_ys_;
  // Per cell, 1 when a row of its 3x3 block holds more points than the
  // quick pass reads (1% of rows): one load a position instead of three ends.
  std::vector<uint8_t> long_block_;
  bool quick_ = false;       // point indices fit FindInBlockQuickly's keys
  bool paired_ = false;      // and FindPairsQuickly's
  bool four_lanes_ = false;  // FindInBlockInFourLanes, not ...TwoLanes
};

// Inline: one call per position, and a call kept `best` in memory between
// the search and its caller.
inline bool NearestSearchGrid::FindTwoNearest(const Vec2& p, TwoNearest& best) const {
  const auto [gx, gy] = CellCoordinates(p);
  if (!BlockInGrid(gx, gy)) return false;
  if (quick_) {
    const int cx = static_cast<int>(gx), cy = static_cast<int>(gy);  // floor: both >= 1
    const double radius1 = Covered(gx, gy, cx - 1, cx + 1, cy - 1, cy + 1);
    if (four_lanes_ ? FindInBlockInFourLanes(p, cx, cy, radius1, best)
                    : FindInBlockInTwoLanes(p, cx, cy, radius1, best)) {
      return true;
    }
  }
  return FindTwoNearestExactly(p, gx, gy, best);
}

inline double NearestSearchGrid::Covered(double gx, double gy, int x_lo, int x_hi, int y_lo,
                                         int y_hi) const {
  return std::min({gx - x_lo, x_hi + 1 - gx, gy - y_lo, y_hi + 1 - gy}) * cell_ - slack_;
}

}  // namespace scallop
