// NearestSearchGrid: bucketing by counting sort, and the two-phase search
// (p's 3x3 block of cells, then the cells the second distance still reaches).
#include "scallop/noise/nearest_search_grid.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <utility>

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

// The quick phase 1 ranks points by a 64-bit key: the bits of the squared
// distance (a non-negative double, so its bits order as it does) with the
// low kIndexBits replaced by the point's index. One compare then orders by
// distance to within 2^-36 relative, and the index comes along.
constexpr int kIndexBits = 16;
constexpr uint64_t kIndexMask = (uint64_t{1} << kIndexBits) - 1;

// Points examined from the start of each row's run of three cells whatever
// the run's length (about 2.6 points in A3 worlds), so that the common case
// has no data-dependent branch; the run's end is passed into later cells and,
// at the end of the array, into kRunPad far pads.
constexpr uint32_t kRunPoints = 4;
constexpr uint32_t kRunPad = kRunPoints;

// Where the pads lie: far enough that their squared distance, about 2^1019,
// exceeds any real one (positions and points are within 2^288), yet finite,
// so that a key keeps a finite double's bits.
constexpr double kPadCoordinate = 0x1.0p+509;

// Keys kLanes at a time, one per lane of a GCC and Clang vector extension:
// two in an SSE2 register, four in an AVX one. Each lane sees the IEEE
// operations scalar code would, in the same order, so it gets the same bits.
// Passing them by value has no fixed ABI without AVX, hence GCC's -Wpsabi
// note; they never leave this file's inlined code, so it is silenced here.
#pragma GCC diagnostic ignored "-Wpsabi"
template <int kLanes>
struct LaneTypes;
template <>
struct LaneTypes<2> {
  using Keys = double __attribute__((vector_size(16)));
  using Bits = uint64_t __attribute__((vector_size(16)));
  static constexpr Bits kIndex = {0, 1};
};
template <>
struct LaneTypes<4> {
  using Keys = double __attribute__((vector_size(32)));
  using Bits = uint64_t __attribute__((vector_size(32)));
  static constexpr Bits kIndex = {0, 1, 2, 3};
};

// Everything below is inlined into its caller, whatever the caller's target:
// the four-lane code then compiles to AVX inside the AVX2 entry point only.
// Hence no lambda, and no function without SCALLOP_INLINE, may take or
// return a lane vector: at -O0 it would be called across two ABIs (KeysOf).
#define SCALLOP_INLINE [[gnu::always_inline]] inline

template <int kLanes>
SCALLOP_INLINE typename LaneTypes<kLanes>::Keys Broadcast(double value) {
  typename LaneTypes<kLanes>::Keys keys;
  for (int lane = 0; lane < kLanes; ++lane) keys[lane] = value;
  return keys;
}

// The keys of points first .. first + kLanes - 1 about (px, py): the bits of
// the squared distance, its low kIndexBits replaced by the point's index.
// A function, not a lambda in its caller: a lambda is not always_inline, and
// at -O0 GCC called it as a function compiled without AVX from the AVX2
// entry point, whose four-lane return then crossed two ABIs (the caller
// expected it in a register, the callee wrote through a hidden pointer
// taken from the register that held the closure): a crash.
template <int kLanes>
SCALLOP_INLINE typename LaneTypes<kLanes>::Keys KeysOf(const double* xs, const double* ys,
                                                       typename LaneTypes<kLanes>::Keys px,
                                                       typename LaneTypes<kLanes>::Keys py,
                                                       uint32_t first) {
  using Keys = typename LaneTypes<kLanes>::Keys;
  using Bits = typename LaneTypes<kLanes>::Bits;
  Keys x, y;
  std::memcpy(&x, xs + first, sizeof(x));
  std::memcpy(&y, ys + first, sizeof(y));
  const Keys dx = px - x, dy = py - y;  // SquaredDistanceFrom's order
  const auto bits = reinterpret_cast<Bits>(dx * dx + dy * dy);
  return reinterpret_cast<Keys>((bits & ~kIndexMask) | (first + LaneTypes<kLanes>::kIndex));
}

// The three smallest keys offered to each lane, in order. Non-negative
// finite doubles order as their bits do, and `a < b ? a : b` is minpd: keys
// are ranked as doubles, without branching on the data. Every min and max
// takes two variables: with a constant operand GCC 12 built compare-and-blend
// sequences instead.
template <int kLanes>
struct SmallestKeys {
  using Keys = typename LaneTypes<kLanes>::Keys;
  Keys first, second, third;

  SCALLOP_INLINE void Start(Keys a, Keys b, Keys c) { Sort(a, b, c); }

  SCALLOP_INLINE void Offer(Keys keys) {
    const Keys high1 = Max(first, keys);
    first = Min(first, keys);
    const Keys high2 = Max(second, high1);
    second = Min(second, high1);
    third = Min(third, high2);
  }

  // Lane 0 gets the three smallest of all lanes.
  SCALLOP_INLINE void MergeAllLanes() {
    static_assert(kLanes == 2 || kLanes == 4);
    MergeLanes<1>();
    if constexpr (kLanes == 4) MergeLanes<2>();
  }

 private:
  SCALLOP_INLINE static Keys Min(Keys a, Keys b) { return a < b ? a : b; }
  SCALLOP_INLINE static Keys Max(Keys a, Keys b) { return a > b ? a : b; }

  SCALLOP_INLINE void Sort(Keys a, Keys b, Keys c) {
    const Keys low = Min(a, b), high = Max(a, b);
    first = Min(low, c);
    const Keys rest = Max(low, c);
    second = Min(high, rest);
    third = Max(high, rest);
  }

  // Each lane gets the three smallest of its own and of lane `lane ^ kSwap`'s:
  // with both sorted, the lane-wise minima of one and the other reversed are
  // the three smallest of the six (a bitonic half-cleaner).
  template <int kSwap>
  SCALLOP_INLINE void MergeLanes() {
    Sort(Min(first, Partners<kSwap>(third)), Min(second, Partners<kSwap>(second)),
         Min(third, Partners<kSwap>(first)));
  }

  // Lane i of the result is lane i ^ kSwap of `keys`: one shuffle with
  // constant lane indices. __builtin_shufflevector is GCC's (12 on) and
  // Clang's; GCC's __builtin_shuffle, with a mask vector, is not Clang's.
  template <int kSwap, int... kLane>
  SCALLOP_INLINE static Keys Partners(Keys keys, std::integer_sequence<int, kLane...>) {
    return __builtin_shufflevector(keys, keys, (kLane ^ kSwap)...);
  }
  template <int kSwap>
  SCALLOP_INLINE static Keys Partners(Keys keys) {
    return Partners<kSwap>(keys, std::make_integer_sequence<int, kLanes>());
  }
};

using Pair = double __attribute__((vector_size(16)));
using PairBits = int64_t __attribute__((vector_size(16)));
using PairCells = int32_t __attribute__((vector_size(8)));
static_assert(sizeof(Pair) == sizeof(Vec2));

SCALLOP_INLINE Pair Broadcast2(double value) { return Pair{value, value}; }

// Whether both lanes of a comparison hold true. GCC 12 tests the lanes one
// by one in six instructions where SSE2 has one.
SCALLOP_INLINE bool BothLanes(PairBits mask) {
#if defined(__SSE2__)
  return __builtin_ia32_movmskpd(reinterpret_cast<Pair>(mask)) == 3;
#else
  return (mask[0] & mask[1]) != 0;
#endif
}

// Both square roots in one instruction, correctly rounded as std::sqrt's
// are; and without std::sqrt's test for a negative argument (errno), which
// GCC 12 kept for a sum of squares.
SCALLOP_INLINE Pair SquareRoots(Pair squares) {
#if defined(__SSE2__)
  return __builtin_ia32_sqrtpd(squares);
#else
  return Pair{std::sqrt(squares[0]), std::sqrt(squares[1])};
#endif
}

bool CpuHasAvx2() {
#if defined(__x86_64__) || defined(__i386__)
  return __builtin_cpu_supports("avx2");
#else
  return false;
#endif
}

}  // namespace

Rect NearestSearchGrid::CoveredSquare(double min_distance, RegionKey key) {
  const Rect region = RegionLayout(min_distance).RegionRect(key);
  const double margin = kMarginCells * min_distance;
  return {region.x0 - margin, region.y0 - margin, region.x1 + margin, region.y1 + margin};
}

NearestSearchGrid::NearestSearchGrid(double min_distance, RegionKey key,
                                     std::span<const Vec2> points, std::span<const uint64_t> ids,
                                     FirstPassWidth width)
    : key_(key),
      cell_(min_distance),
      inverse_cell_(1.0 / min_distance),
      slack_(kSlackInD * min_distance),
      four_lanes_(width == FirstPassWidth::kWidest && FourLanesAvailable()) {
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
  xs_.resize(cell_start_.back() + kRunPad, kPadCoordinate);
  ys_.resize(cell_start_.back() + kRunPad, kPadCoordinate);
  ids_.resize(cell_start_.back() + kRunPad, 0);
  quick_ = ids_.size() <= kIndexMask + 1;
  // Stable within a cell (input order), so a grid is a pure function of its input.
  for (size_t k = 0; k < points.size(); ++k) {
    if (cell_of[k] < 0) continue;
    const uint32_t slot = counts[cell_of[k]]++;
    xs_[slot] = points[k].x;
    ys_[slot] = points[k].y;
    ids_[slot] = ids[k];
  }
  long_block_.assign(kSide * kSide, 0);
  for (int cy = 1; cy < kSide - 1; ++cy) {
    for (int cx = 1; cx < kSide - 1; ++cx) {
      for (int row = cy - 1; row <= cy + 1; ++row) {
        const uint32_t run = cell_start_[row * kSide + cx + 2] - cell_start_[row * kSide + cx - 1];
        if (run > kRunPoints) long_block_[cy * kSide + cx] = 1;
      }
    }
  }
}

size_t NearestSearchGrid::Bytes() const {
  return sizeof(*this) + cell_start_.capacity() * sizeof(uint32_t) + long_block_.capacity() +
         (xs_.capacity() + ys_.capacity()) * sizeof(double) + ids_.capacity() * sizeof(uint64_t);
}

void NearestSearchGrid::ScanRow(int row, int first, int last, const Vec2& p,
                                TwoNearest& best) const {
  const uint32_t end = cell_start_[row * kSide + last + 1];
  for (uint32_t k = cell_start_[row * kSide + first]; k < end; ++k) {
    const Vec2 q = Point(k);
    OfferCandidate(SquaredDistanceFrom(p, q), ids_[k], q, best);
  }
}

template <int kLanes, int kPositions>
SCALLOP_INLINE unsigned NearestSearchGrid::FindInBlocksQuickly(const BlockQuery* queries) const {
  using Keys = typename LaneTypes<kLanes>::Keys;
  static_assert(kRunPoints % kLanes == 0);
  // Examines every point of each position's 3x3 block, and some beyond it
  // (later cells of a row, the far pads, possibly a point twice): extra
  // points are real, or farther than any block reaches, so they cannot make
  // a wrong answer look right. Each step runs for every position before the
  // next step: the positions' chains of dependent loads and compares are
  // independent, and side by side the CPU overlaps them.
  const double* const xs = xs_.data();
  const double* const ys = ys_.data();
  Keys px[kPositions], py[kPositions];
  // Row r of query q's block starts at runs[q][r * kSide] and ends at runs[q][r * kSide + 3].
  const uint32_t* runs[kPositions];
  uint32_t first[kPositions][3];
  // Longer runs are rare (1% of rows): one branch for them all.
  bool long_run = false;
  for (int q = 0; q < kPositions; ++q) {
    px[q] = Broadcast<kLanes>(queries[q].p->x);
    py[q] = Broadcast<kLanes>(queries[q].p->y);
    runs[q] = cell_start_.data() + queries[q].cell - kSide - 1;
    for (int r = 0; r < 3; ++r) first[q][r] = runs[q][r * kSide];
    long_run |= long_block_[queries[q].cell] != 0;
  }
  // Several positions at once leave them to the one-position pass: its loop
  // here kept every position's keys in memory, not registers.
  if constexpr (kPositions > 1) {
    if (long_run) [[unlikely]]
      return kAnswerEachAlone;
  }
  constexpr int kVectors = 3 * kRunPoints / kLanes;  // for the runs' first kRunPoints
  static_assert(kVectors >= 3);
  SmallestKeys<kLanes> keys[kPositions];
  for (int q = 0; q < kPositions; ++q) {
    Keys fixed[kVectors];
    for (int v = 0; v < kVectors; ++v) {
      fixed[v] = KeysOf<kLanes>(xs, ys, px[q], py[q],
                                first[q][v * kLanes / kRunPoints] + v * kLanes % kRunPoints);
    }
    keys[q].Start(fixed[0], fixed[1], fixed[2]);
    for (int v = 3; v < kVectors; ++v) keys[q].Offer(fixed[v]);
  }
  if (long_run) [[unlikely]] {
    for (int q = 0; q < kPositions; ++q) {
      for (int r = 0; r < 3; ++r) {
        for (uint32_t k = first[q][r] + kRunPoints; k < runs[q][r * kSide + 3]; k += kLanes)
          keys[q].Offer(KeysOf<kLanes>(xs, ys, px[q], py[q], k));
      }
    }
  }
  unsigned certified = 0;
  for (int q = 0; q < kPositions; ++q) {
    keys[q].MergeAllLanes();
    // Distinct truncated distances: the first key's point is strictly nearer
    // than every other point examined, and the second's strictly second (a
    // point examined twice would tie with itself). Ties by id cannot arise,
    // so the exact order by (squared, id) is this one. Otherwise (ties, or
    // distances equal to 2^-36), the exact scan decides.
    const auto key1 = std::bit_cast<uint64_t>(keys[q].first[0]);
    const auto key2 = std::bit_cast<uint64_t>(keys[q].second[0]);
    const auto key3 = std::bit_cast<uint64_t>(keys[q].third[0]);
    const bool distinct = ((key1 >> kIndexBits) != (key2 >> kIndexBits)) &
                          ((key2 >> kIndexBits) != (key3 >> kIndexBits));
    // Every index is a point's or a pad's, so the reads below are in bounds
    // whether or not the answer stands: no branch until the caller's.
    const auto i1 = static_cast<uint32_t>(key1 & kIndexMask);
    const auto i2 = static_cast<uint32_t>(key2 & kIndexMask);
    const Vec2& p = *queries[q].p;
    TwoNearest& best = *queries[q].best;
    best.squared1 = SquaredDistanceFrom(p, Point(i1));
    best.squared2 = SquaredDistanceFrom(p, Point(i2));
    const double radius1 = queries[q].radius1;
    // Else phase 2 is needed (or a pad is among the two).
    const bool within = best.squared2 <= radius1 * radius1;
    best.id1 = ids_[i1];
    best.id2 = ids_[i2];
    // Each point as one 16-byte store: the caller reads it so, and one built
    // from two 8-byte stores would stall that read (no store forwarding).
    const Pair point1 = {xs_[i1], ys_[i1]}, point2 = {xs_[i2], ys_[i2]};
    best.point1 = std::bit_cast<Vec2>(point1);
    best.point2 = std::bit_cast<Vec2>(point2);
    certified |= static_cast<unsigned>(distinct & within) << q;
  }
  return certified;
}

bool NearestSearchGrid::FindInBlockInTwoLanes(const Vec2& p, int cx, int cy, double radius1,
                                              TwoNearest& best) const {
  const BlockQuery query{&p, cy * kSide + cx, radius1, &best};
  return FindInBlocksQuickly<2, 1>(&query) != 0;
}

SCALLOP_INLINE bool NearestSearchGrid::LocateBlock(const Vec2& p, int& cell,
                                                   double& radius1) const {
  Pair position;
  std::memcpy(&position, &p, sizeof(position));
  const Pair g = (position - std::bit_cast<Pair>(origin_)) * Broadcast2(inverse_cell_);
  if (!BothLanes((g >= Broadcast2(1)) & (g < Broadcast2(kSide - 1)))) return false;
  // Exact, as Covered's terms are: c = floor(g) >= 1, so g - c (Sterbenz),
  // 1 - (g - c) and 1 + either are multiples of g's ulp in [0, 2]. Then
  // min(g - (c - 1), (c + 2) - g) over both axes is 1 + min(f, 1 - f).
  const PairCells c = __builtin_convertvector(g, PairCells);
  const Pair f = g - __builtin_convertvector(c, Pair);
  const Pair rest = Broadcast2(1) - f;
  const Pair nearer = f < rest ? f : rest;
  radius1 = (1 + std::min(nearer[0], nearer[1])) * cell_ - slack_;
  cell = c[1] * kSide + c[0];
  return true;
}

namespace {
// The basis from a certified quick pass, its square roots in one instruction.
SCALLOP_INLINE void StoreBasis(const TwoNearest& best, NearestPoint& out) {
  const Pair f = SquareRoots(Pair{best.squared1, best.squared2});
  out = {.id = best.id1,
         .position = best.point1,
         .f1 = f[0],
         .f2 = f[1],
         .second_id = best.id2,
         .cell_value = CellValue(best.id1)};
}
}  // namespace

template <int kLanes>
SCALLOP_INLINE void NearestSearchGrid::AnswerEachIn(std::span<const IndexedPosition> positions,
                                                    NearestPoint* results,
                                                    std::vector<uint32_t>& refused) const {
  const auto count = static_cast<uint32_t>(positions.size());
  uint32_t k = 0;
  for (; k + 2 <= count; k += 2) {
    const IndexedPosition& entry0 = positions[k];
    const IndexedPosition& entry1 = positions[k + 1];
    TwoNearest best[2];
    BlockQuery queries[2] = {{&entry0.position, 0, 0, &best[0]},
                             {&entry1.position, 0, 0, &best[1]}};
    const bool located = LocateBlock(entry0.position, queries[0].cell, queries[0].radius1) &
                         LocateBlock(entry1.position, queries[1].cell, queries[1].radius1);
    if (!(quick_ && located)) [[unlikely]] {
      AnswerAlone(entry0, k, results, refused);
      AnswerAlone(entry1, k + 1, results, refused);
      continue;
    }
    const unsigned certified = FindInBlocksQuickly<kLanes, 2>(queries);
    if (certified == kAnswerEachAlone) [[unlikely]] {
      AnswerAlone(entry0, k, results, refused);
      AnswerAlone(entry1, k + 1, results, refused);
      continue;
    }
    if (certified & 1u) {
      StoreBasis(best[0], results[entry0.index]);
    } else {
      AnswerExactly(entry0, k, results, refused);
    }
    if (certified & 2u) {
      StoreBasis(best[1], results[entry1.index]);
    } else {
      AnswerExactly(entry1, k + 1, results, refused);
    }
  }
  if (k < count) AnswerAlone(positions[k], k, results, refused);
}

void NearestSearchGrid::AnswerEach(std::span<const IndexedPosition> positions,
                                   std::span<NearestPoint> results,
                                   std::vector<uint32_t>& refused) const {
  if (four_lanes_) {
    AnswerEachInFourLanes(positions, results.data(), refused);
  } else {
    AnswerEachInTwoLanes(positions, results.data(), refused);
  }
}

void NearestSearchGrid::AnswerAlone(const IndexedPosition& entry, uint32_t offset,
                                    NearestPoint* results, std::vector<uint32_t>& refused) const {
  TwoNearest best;
  if (FindTwoNearest(entry.position, best)) {
    results[entry.index] = ToNearestPoint(best);
  } else {
    refused.push_back(offset);
  }
}

void NearestSearchGrid::AnswerExactly(const IndexedPosition& entry, uint32_t offset,
                                      NearestPoint* results, std::vector<uint32_t>& refused) const {
  const auto [gx, gy] = CellCoordinates(entry.position);
  TwoNearest best;
  if (FindTwoNearestExactly(entry.position, gx, gy, best)) {
    results[entry.index] = ToNearestPoint(best);
  } else {
    refused.push_back(offset);
  }
}

void NearestSearchGrid::AnswerEachInTwoLanes(std::span<const IndexedPosition> positions,
                                             NearestPoint* results,
                                             std::vector<uint32_t>& refused) const {
  AnswerEachIn<2>(positions, results, refused);
}

#if defined(__x86_64__) || defined(__i386__)
__attribute__((target("avx2"))) bool NearestSearchGrid::FindInBlockInFourLanes(
    const Vec2& p, int cx, int cy, double radius1, TwoNearest& best) const {
  const BlockQuery query{&p, cy * kSide + cx, radius1, &best};
  return FindInBlocksQuickly<4, 1>(&query) != 0;
}

__attribute__((target("avx2"))) void NearestSearchGrid::AnswerEachInFourLanes(
    std::span<const IndexedPosition> positions, NearestPoint* results,
    std::vector<uint32_t>& refused) const {
  AnswerEachIn<4>(positions, results, refused);
}
#else
bool NearestSearchGrid::FindInBlockInFourLanes(const Vec2& p, int cx, int cy, double radius1,
                                               TwoNearest& best) const {
  return FindInBlockInTwoLanes(p, cx, cy, radius1, best);
}

void NearestSearchGrid::AnswerEachInFourLanes(std::span<const IndexedPosition> positions,
                                              NearestPoint* results,
                                              std::vector<uint32_t>& refused) const {
  AnswerEachInTwoLanes(positions, results, refused);
}
#endif

bool NearestSearchGrid::FourLanesAvailable() {
  static const bool available = CpuHasAvx2();
  return available;
}

bool NearestSearchGrid::FindTwoNearestExactly(const Vec2& p, double gx, double gy,
                                              TwoNearest& best) const {
  const int cx = static_cast<int>(gx), cy = static_cast<int>(gy);  // floor: both >= 1
  // Phase 1: p's cell and its 8 neighbours hold F1 and F2 most of the time.
  best = TwoNearest{};
  for (int row = cy - 1; row <= cy + 1; ++row) ScanRow(row, cx - 1, cx + 1, p, best);
  const double radius1 = Covered(gx, gy, cx - 1, cx + 1, cy - 1, cy + 1);
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
  const double radius2 = Covered(gx, gy, x_lo, x_hi, y_lo, y_hi);
  return best.squared2 <= radius2 * radius2;
}

}  // namespace scallop
