// NearestSearchGrid: bucketing by counting sort, and the two-phase search
// (p's 3x3 block of cells, then the cells the second distance still reaches).
#include "scallop/noise/nearest_search_grid.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <utility>

#include "scallop/noise/coordinate_pair.h"

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
  static constexpr Bits kIndex = {0, 2, 1, 3};  // KeysOf's lane order
};

// The paired pass (FindPairsQuickly) ranks floats: squared distances in cell
// units from float cell coordinates, their low kPairIndexBits replaced by
// the point's index. A grid's points are then at most 2^kPairIndexBits, pads
// included (a maximal world's grid holds at most about 620: 484 cells at
// the densest packing). Truncation leaves 13 bits: a key's value T and the
// float distance F it came from have T <= F < T (1 + 2^-13).
constexpr int kPairIndexBits = 10;
constexpr uint32_t kPairIndexMask = (uint32_t{1} << kPairIndexBits) - 1;

// Where the pads lie in cell units: farther than any block reaches, and a
// float squared distance (2^81) far from overflowing.
constexpr float kPadCell = 0x1.0p+40f;

// kLanes float keys, the first half for one position and the second half for
// the other of a pair: four lanes in SSE2, eight in AVX.
template <int kLanes>
struct PairLaneTypes;
template <>
struct PairLaneTypes<4> {
  using Keys = float __attribute__((vector_size(16)));
  using Bits = uint32_t __attribute__((vector_size(16)));
  using Half = float __attribute__((vector_size(8)));
  static constexpr Bits kIndex = {0, 1, 0, 1};
};
template <>
struct PairLaneTypes<8> {
  using Keys = float __attribute__((vector_size(32)));
  using Bits = uint32_t __attribute__((vector_size(32)));
  using Half = float __attribute__((vector_size(16)));
  static constexpr Bits kIndex = {0, 1, 2, 3, 0, 1, 2, 3};
};
using Floats4 = float __attribute__((vector_size(16)));
using Floats4Bits = uint32_t __attribute__((vector_size(16)));

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
// The lanes need not hold the points in order (the index rides along): four
// lanes hold first, first + 2, first + 1, first + 3, which two in-lane
// unpacks of the records' coordinate pairs give.
// A function, not a lambda in its caller: a lambda is not always_inline, and
// at -O0 GCC called it as a function compiled without AVX from the AVX2
// entry point, whose four-lane return then crossed two ABIs (the caller
// expected it in a register, the callee wrote through a hidden pointer
// taken from the register that held the closure): a crash.
template <int kLanes>
SCALLOP_INLINE typename LaneTypes<kLanes>::Keys KeysOf(const SearchGridPoint* points,
                                                       typename LaneTypes<kLanes>::Keys px,
                                                       typename LaneTypes<kLanes>::Keys py,
                                                       uint32_t first) {
  using Keys = typename LaneTypes<kLanes>::Keys;
  using Bits = typename LaneTypes<kLanes>::Bits;
  Keys x, y;
  const Pair a = LoadPair(points[first].position), b = LoadPair(points[first + 1].position);
  if constexpr (kLanes == 2) {
    x = __builtin_shufflevector(a, b, 0, 2);
    y = __builtin_shufflevector(a, b, 1, 3);
  } else {
    const Pair c = LoadPair(points[first + 2].position), d = LoadPair(points[first + 3].position);
    const Keys ab = __builtin_shufflevector(a, b, 0, 1, 2, 3);
    const Keys cd = __builtin_shufflevector(c, d, 0, 1, 2, 3);
    x = __builtin_shufflevector(ab, cd, 0, 4, 2, 6);
    y = __builtin_shufflevector(ab, cd, 1, 5, 3, 7);
  }
  const Keys dx = px - x, dy = py - y;  // SquaredDistanceFrom's order
  const auto bits = reinterpret_cast<Bits>(dx * dx + dy * dy);
  return reinterpret_cast<Keys>((bits & ~kIndexMask) | (first + LaneTypes<kLanes>::kIndex));
}

// The float keys of a pair: points first_a .. first_a + kLanes / 2 - 1 about
// (gx_a, gy_a) in the first half, first_b .. about (gx_b, gy_b) in the second.
template <int kLanes>
SCALLOP_INLINE typename PairLaneTypes<kLanes>::Keys PairKeysOf(
    const float* gxs, const float* gys, typename PairLaneTypes<kLanes>::Keys gx,
    typename PairLaneTypes<kLanes>::Keys gy, uint32_t first_a, uint32_t first_b,
    typename PairLaneTypes<kLanes>::Bits index) {
  using Types = PairLaneTypes<kLanes>;
  using Keys = typename Types::Keys;
  using Bits = typename Types::Bits;
  typename Types::Half xa, xb, ya, yb;
  std::memcpy(&xa, gxs + first_a, sizeof(xa));
  std::memcpy(&xb, gxs + first_b, sizeof(xb));
  std::memcpy(&ya, gys + first_a, sizeof(ya));
  std::memcpy(&yb, gys + first_b, sizeof(yb));
  Keys x, y;
  if constexpr (kLanes == 4) {
    x = __builtin_shufflevector(xa, xb, 0, 1, 2, 3);
    y = __builtin_shufflevector(ya, yb, 0, 1, 2, 3);
  } else {
    x = __builtin_shufflevector(xa, xb, 0, 1, 2, 3, 4, 5, 6, 7);
    y = __builtin_shufflevector(ya, yb, 0, 1, 2, 3, 4, 5, 6, 7);
  }
  const Keys dx = gx - x, dy = gy - y;
  const auto bits = reinterpret_cast<Bits>(dx * dx + dy * dy);
  return reinterpret_cast<Keys>((bits & ~kPairIndexMask) | index);
}

// The first points of a pair's three rows, {a0, a1, a2, 0, b0, b1, b2, 0},
// and row kRow's broadcast to each position's half of kLanes lanes.
using PairRows = uint32_t __attribute__((vector_size(32)));
template <int kLanes, int kRow>
SCALLOP_INLINE typename PairLaneTypes<kLanes>::Bits RowIndex(PairRows rows) {
  constexpr int a = kRow, b = 4 + kRow;
  if constexpr (kLanes == 4) {
    return __builtin_shufflevector(rows, rows, a, a, b, b);
  } else {
    return __builtin_shufflevector(rows, rows, a, a, a, a, b, b, b, b);
  }
}

// {a[0], b[0], a[h], b[h]} for h half the lanes: an unpack and, for eight
// lanes, the two 128-bit halves side by side (no lane-crossing permute).
template <typename Keys>
SCALLOP_INLINE Floats4 FirstLanesOfHalves(Keys a, Keys b) {
  if constexpr (sizeof(Keys) == 16) {
    return __builtin_shufflevector(a, b, 0, 4, 2, 6);
  } else {
    const Keys unpacked = __builtin_shufflevector(a, b, 0, 8, 1, 9, 4, 12, 5, 13);
    return __builtin_shufflevector(unpacked, unpacked, 0, 1, 4, 5);
  }
}

// The three smallest keys offered to each lane, in order. Non-negative
// finite doubles order as their bits do, and `a < b ? a : b` is minpd: keys
// are ranked as doubles, without branching on the data. Every min and max
// takes two variables: with a constant operand GCC 12 built compare-and-blend
// sequences instead.
template <typename Keys>
struct SmallestKeys {
  static constexpr int kLanes = sizeof(Keys) / sizeof(Keys{}[0]);
  Keys first, second, third;

  SCALLOP_INLINE void Start(Keys a, Keys b, Keys c) { Sort(a, b, c); }

  SCALLOP_INLINE void Offer(Keys keys) {
    const Keys high1 = Max(first, keys);
    first = Min(first, keys);
    const Keys high2 = Max(second, high1);
    second = Min(second, high1);
    third = Min(third, high2);
  }

  // The first lane of each group of kGroup lanes gets the three smallest of
  // its group: all lanes for one position's keys, half of them for a pair's.
  template <int kGroup>
  SCALLOP_INLINE void MergeGroupsOf() {
    static_assert(kGroup == 2 || kGroup == 4);
    MergeLanes<1>();
    if constexpr (kGroup == 4) MergeLanes<2>();
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
  // the three smallest of the six (a bitonic half-cleaner), and they rise
  // then fall, which two levels sort (SortRisingFalling) where three would
  // for any three.
  template <int kSwap>
  SCALLOP_INLINE void MergeLanes() {
    SortRisingFalling(Min(first, Partners<kSwap>(third)), Min(second, Partners<kSwap>(second)),
                      Min(third, Partners<kSwap>(first)));
  }

  // Sorts a <= ... b ... >= c (a sequence that rises then falls, either part
  // possibly empty): with -infinity before it, it is bitonic, and a bitonic
  // sorter of four gives min(a, c), then min(b, max(a, c)), then the rest.
  SCALLOP_INLINE void SortRisingFalling(Keys a, Keys b, Keys c) {
    const Keys high = Max(a, c);
    first = Min(a, c);
    second = Min(b, high);
    third = Max(b, high);
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

// Both positions of a pair, x and y: AVX lanes, or two SSE2 registers.
using Quad = double __attribute__((vector_size(32)));
using QuadBits = int64_t __attribute__((vector_size(32)));
using QuadCells = int32_t __attribute__((vector_size(16)));
SCALLOP_INLINE Quad Broadcast4(double value) { return Quad{value, value, value, value}; }

// Bit k: lane k of a comparison of four floats holds true.
SCALLOP_INLINE unsigned FloatLanesSet(Floats4Bits mask) {
#if defined(__SSE2__)
  return static_cast<unsigned>(__builtin_ia32_movmskps(reinterpret_cast<Floats4>(mask)));
#else
  unsigned bits = 0;
  for (int lane = 0; lane < 4; ++lane) bits |= (mask[lane] != 0 ? 1u : 0u) << lane;
  return bits;
#endif
}

bool CpuHasAvx2() {
#if defined(__x86_64__) || defined(__i386__)
  return __builtin_cpu_supports("avx2");
#else
  return false;
#endif
}

// Lines of the next grid prefetched for each pair of positions answered:
// 1.5 a position, so that a group of a few hundred positions (256 in a warm
// 256 d square) covers the next grid's 19 KB before it is needed.
constexpr int kPrefetchLinesPerPair = 3;
constexpr uintptr_t kLineBytes = 64;

}  // namespace

// Walks a grid's arrays line by line, prefetching each into L2 (prefetcht1,
// so as not to crowd L1 with a grid not yet read), a few lines a step.
class NearestSearchGrid::LinePrefetcher {
 public:
  explicit LinePrefetcher(const NearestSearchGrid* grid) {
    if (grid == nullptr) return;
    arrays_ = {Bytes(grid->cell_start_), Bytes(grid->long_block_), Bytes(grid->cell_xs_),
               Bytes(grid->cell_ys_), Bytes(grid->points_)};
    next_array_ = 0;
  }

  // kLines lines from the current one on, with one test a step: a test and
  // a move a line, its position kept on the stack, cost the paired loop
  // more than its prefetches did. A step may reach up to kLines - 1 lines
  // past its array's end, into whatever follows in memory (a hint, so
  // harmless); the next step starts the next array.
  template <int kLines>
  SCALLOP_INLINE void Step() {
    if (line_ >= end_ && !StartNextArray()) [[unlikely]]
      return;
    for (int k = 0; k < kLines; ++k) {
      __builtin_prefetch(reinterpret_cast<const void*>(line_ + k * kLineBytes), 0, 2);
    }
    line_ += kLines * kLineBytes;
  }

 private:
  // Moves to the next array; false when every array has been walked.
  bool StartNextArray() {
    if (next_array_ == kArrays) return false;
    line_ = LineOf(arrays_[next_array_].begin);
    end_ = arrays_[next_array_].end;
    ++next_array_;
    return true;
  }

  struct ByteRange {
    uintptr_t begin = 0, end = 0;
  };
  static constexpr int kArrays = 5;
  template <typename T>
  static ByteRange Bytes(const std::vector<T>& array) {
    const auto begin = reinterpret_cast<uintptr_t>(array.data());
    return {begin, begin + array.size() * sizeof(T)};
  }
  // The start of the line holding `address`.
  static uintptr_t LineOf(uintptr_t address) { return address & ~(kLineBytes - 1); }

  std::array<ByteRange, kArrays> arrays_;
  int next_array_ = kArrays;  // kArrays: no array (left) to start
  uintptr_t line_ = 0;        // the next line to prefetch, in [.., end_) of the current array
  uintptr_t end_ = 0;
};

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
  points_.resize(cell_start_.back() + kRunPad,
                 {.position = {kPadCoordinate, kPadCoordinate}, .id = 0, .cell_value = 0});
  cell_xs_.resize(cell_start_.back() + kRunPad, kPadCell);
  cell_ys_.resize(cell_start_.back() + kRunPad, kPadCell);
  quick_ = points_.size() <= kIndexMask + 1;
  paired_ = points_.size() <= kPairIndexMask + 1;
  // Stable within a cell (input order), so a grid is a pure function of its input.
  for (size_t k = 0; k < points.size(); ++k) {
    if (cell_of[k] < 0) continue;
    const uint32_t slot = counts[cell_of[k]]++;
    points_[slot] = {.position = points[k], .id = ids[k], .cell_value = CellValue(ids[k])};
    // CellCoordinates' g, in [0, kSide) here, rounded to float.
    cell_xs_[slot] = static_cast<float>((points[k].x - origin_.x) * inverse_cell_);
    cell_ys_[slot] = static_cast<float>((points[k].y - origin_.y) * inverse_cell_);
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
         points_.capacity() * sizeof(SearchGridPoint) +
         (cell_xs_.capacity() + cell_ys_.capacity()) * sizeof(float);
}

void NearestSearchGrid::ScanRow(int row, int first, int last, const Vec2& p,
                                TwoNearest& best) const {
  const uint32_t end = cell_start_[row * kSide + last + 1];
  for (uint32_t k = cell_start_[row * kSide + first]; k < end; ++k) {
    const SearchGridPoint& q = points_[k];
    OfferCandidate(SquaredDistanceFrom(p, q.position), q.id, q.position, best);
  }
}

SCALLOP_INLINE bool NearestSearchGrid::TakeFound(const BlockQuery& query, uint32_t i1,
                                                 uint32_t i2) const {
  const Vec2& p = *query.p;
  TwoNearest& best = *query.best;
  const SearchGridPoint& found1 = points_[i1];
  const SearchGridPoint& found2 = points_[i2];
  best.squared1 = SquaredDistanceFrom(p, found1.position);
  best.squared2 = SquaredDistanceFrom(p, found2.position);
  best.id1 = found1.id;
  best.id2 = found2.id;
  // Each point as one 16-byte store: the caller reads it so, and one built
  // from two 8-byte stores would stall that read (no store forwarding).
  best.point1 = found1.position;
  best.point2 = found2.position;
  // Else phase 2 is needed (or a pad is among the two).
  return best.squared2 <= query.radius1 * query.radius1;
}

SCALLOP_INLINE bool NearestSearchGrid::StoreFound(const PairQuery& query, bool ordered, uint32_t i1,
                                                  uint32_t i2) const {
  const Vec2& p = *query.p;
  const SearchGridPoint& found1 = points_[i1];
  const SearchGridPoint& found2 = points_[i2];
  const double squared1 = SquaredDistanceFrom(p, found1.position);
  const double squared2 = SquaredDistanceFrom(p, found2.position);
  // Else phase 2 is needed (or a pad is among the two).
  const bool certified = ordered & (squared2 <= query.radius1 * query.radius1);
  if (certified) [[likely]] {
    // ToNearestPoint's fields, its square roots in one instruction.
    const Pair f = SquareRoots(Pair{squared1, squared2});
    *query.out = {.id = found1.id,
                  .position = found1.position,
                  .f1 = f[0],
                  .f2 = f[1],
                  .second_id = found2.id,
                  .cell_value = found1.cell_value};
  }
  return certified;
}

template <int kLanes>
SCALLOP_INLINE bool NearestSearchGrid::FindInBlockQuickly(const Vec2& p, int cx, int cy,
                                                          double radius1, TwoNearest& best) const {
  using Keys = typename LaneTypes<kLanes>::Keys;
  static_assert(kRunPoints % kLanes == 0);
  const BlockQuery query{.p = &p, .best = &best, .cell = cy * kSide + cx, .radius1 = radius1};
  // Examines every point of the position's 3x3 block, and some beyond it
  // (later cells of a row, the far pads, possibly a point twice): extra
  // points are real, or farther than any block reaches, so they cannot make
  // a wrong answer look right.
  const SearchGridPoint* const points = points_.data();
  const Keys px = Broadcast<kLanes>(query.p->x), py = Broadcast<kLanes>(query.p->y);
  // Row r of the block starts at runs[r * kSide] and ends at runs[r * kSide + 3].
  const uint32_t* const runs = cell_start_.data() + query.cell - kSide - 1;
  uint32_t first[3];
  for (int r = 0; r < 3; ++r) first[r] = runs[r * kSide];
  constexpr int kVectors = 3 * kRunPoints / kLanes;  // for the runs' first kRunPoints
  static_assert(kVectors >= 3);
  SmallestKeys<Keys> keys;
  Keys fixed[kVectors];
  for (int v = 0; v < kVectors; ++v) {
    fixed[v] =
        KeysOf<kLanes>(points, px, py, first[v * kLanes / kRunPoints] + v * kLanes % kRunPoints);
  }
  keys.Start(fixed[0], fixed[1], fixed[2]);
  for (int v = 3; v < kVectors; ++v) keys.Offer(fixed[v]);
  // Longer runs are rare (1% of rows).
  if (long_block_[query.cell] != 0) [[unlikely]] {
    for (int r = 0; r < 3; ++r) {
      for (uint32_t k = first[r] + kRunPoints; k < runs[r * kSide + 3]; k += kLanes)
        keys.Offer(KeysOf<kLanes>(points, px, py, k));
    }
  }
  keys.template MergeGroupsOf<kLanes>();
  // Distinct truncated distances: the first key's point is strictly nearer
  // than every other point examined, and the second's strictly second (a
  // point examined twice would tie with itself). Ties by id cannot arise,
  // so the exact order by (squared, id) is this one. Otherwise (ties, or
  // distances equal to 2^-36), the exact scan decides.
  const auto key1 = std::bit_cast<uint64_t>(keys.first[0]);
  const auto key2 = std::bit_cast<uint64_t>(keys.second[0]);
  const auto key3 = std::bit_cast<uint64_t>(keys.third[0]);
  const bool distinct = ((key1 >> kIndexBits) != (key2 >> kIndexBits)) &
                        ((key2 >> kIndexBits) != (key3 >> kIndexBits));
  // Every index is a point's or a pad's, so the reads below are in bounds
  // whether or not the answer stands: no branch until the caller's.
  const auto i1 = static_cast<uint32_t>(key1 & kIndexMask);
  const auto i2 = static_cast<uint32_t>(key2 & kIndexMask);
  const bool within = TakeFound(query, i1, i2);
  return distinct & within;
}

template <int kLanes, int kPairs, typename CellFloats>
SCALLOP_INLINE unsigned NearestSearchGrid::FindPairsQuickly(const PairQuery* queries,
                                                            const CellFloats* g) const {
  using Types = PairLaneTypes<kLanes>;
  using Keys = typename Types::Keys;
  constexpr int kHalf = kLanes / 2;  // lanes a position
  static_assert(kRunPoints % kHalf == 0);
  // As FindInBlockQuickly, for pairs: the same points examined, and the
  // same exact distances recomputed for the two found. Each step runs for
  // every pair before the next: the pairs' chains of dependent loads,
  // minima and maxima are independent, and side by side the CPU overlaps them.
  bool long_run = false;
  for (int q = 0; q < 2 * kPairs; ++q) long_run |= long_block_[queries[q].cell] != 0;
  if (long_run) [[unlikely]]
    return kAnswerEachAlone;
  constexpr int kParts = kRunPoints / kHalf;  // vectors a row
  SmallestKeys<Keys> keys[kPairs];
  for (int pair = 0; pair < kPairs; ++pair) {
    // Each position's cell coordinates broadcast to its half.
    const CellFloats gp = g[pair];
    Keys gx, gy;
    if constexpr (kLanes == 4) {
      gx = __builtin_shufflevector(gp, gp, 0, 0, 2, 2);
      gy = __builtin_shufflevector(gp, gp, 1, 1, 3, 3);
    } else {
      gx = __builtin_shufflevector(gp, gp, 0, 0, 0, 0, 2, 2, 2, 2);
      gy = __builtin_shufflevector(gp, gp, 1, 1, 1, 1, 3, 3, 3, 3);
    }
    // The rows' first points, each broadcast to its half by one in-lane shuffle.
    // (Read here, not with the long rows' test above: the twelve of two
    // pairs read there outlived the registers and went through the stack.)
    uint32_t a[3], b[3];
    const uint32_t* const runs_a = cell_start_.data() + queries[2 * pair].cell - kSide - 1;
    const uint32_t* const runs_b = cell_start_.data() + queries[2 * pair + 1].cell - kSide - 1;
    for (int r = 0; r < 3; ++r) {
      a[r] = runs_a[r * kSide];
      b[r] = runs_b[r * kSide];
    }
    const PairRows rows = {a[0], a[1], a[2], 0, b[0], b[1], b[2], 0};
    const typename Types::Bits row_index[3] = {RowIndex<kLanes, 0>(rows) + Types::kIndex,
                                               RowIndex<kLanes, 1>(rows) + Types::kIndex,
                                               RowIndex<kLanes, 2>(rows) + Types::kIndex};
    Keys fixed[3 * kParts];
    for (int r = 0; r < 3; ++r) {
      for (int part = 0; part < kParts; ++part) {
        fixed[r * kParts + part] = PairKeysOf<kLanes>(
            cell_xs_.data(), cell_ys_.data(), gx, gy, a[r] + part * kHalf, b[r] + part * kHalf,
            row_index[r] + static_cast<uint32_t>(part * kHalf));
      }
    }
    keys[pair].Start(fixed[0], fixed[1], fixed[2]);
    for (int v = 3; v < 3 * kParts; ++v) keys[pair].Offer(fixed[v]);
  }
  for (int pair = 0; pair < kPairs; ++pair) keys[pair].template MergeGroupsOf<kHalf>();
  unsigned certified = 0;
  for (int pair = 0; pair < kPairs; ++pair) {
    // Lanes: position 0's first and second, position 1's first and second;
    // and the same positions' second and third.
    const Floats4 low = FirstLanesOfHalves(keys[pair].first, keys[pair].second);
    const Floats4 high = FirstLanesOfHalves(keys[pair].second, keys[pair].third);
    // Apart: high > low (1 + 2^-11) + 2^-11 on the truncated values, so the
    // exact distances order as the keys do (docs/noise.md, "The paired pass").
    const Floats4Bits low_bits = reinterpret_cast<Floats4Bits>(low);
    const Floats4 low_value = reinterpret_cast<Floats4>(low_bits & ~kPairIndexMask);
    const Floats4 high_value =
        reinterpret_cast<Floats4>(reinterpret_cast<Floats4Bits>(high) & ~kPairIndexMask);
    const Floats4 margin = {0x1.0p-11f, 0x1.0p-11f, 0x1.0p-11f, 0x1.0p-11f};
    const Floats4 scale = {1 + 0x1.0p-11f, 1 + 0x1.0p-11f, 1 + 0x1.0p-11f, 1 + 0x1.0p-11f};
    const unsigned apart = FloatLanesSet(high_value > low_value * scale + margin);
    const Floats4Bits index = low_bits & kPairIndexMask;
    for (int q = 0; q < 2; ++q) {
      const bool ordered = ((apart >> (2 * q)) & 3) == 3;
      const bool stored =
          StoreFound(queries[2 * pair + q], ordered, index[2 * q], index[2 * q + 1]);
      certified |= static_cast<unsigned>(stored) << (2 * pair + q);
    }
  }
  return certified;
}

bool NearestSearchGrid::FindInBlockInTwoLanes(const Vec2& p, int cx, int cy, double radius1,
                                              TwoNearest& best) const {
  return FindInBlockQuickly<2>(p, cx, cy, radius1, best);
}

template <typename CellFloats>
SCALLOP_INLINE bool NearestSearchGrid::LocatePair(PairQuery* queries, CellFloats& g_floats) const {
  const Pair a = LoadPair(*queries[0].p), b = LoadPair(*queries[1].p);
  const Pair origin = std::bit_cast<Pair>(origin_);
  const Quad g = (__builtin_shufflevector(a, b, 0, 1, 2, 3) -
                  __builtin_shufflevector(origin, origin, 0, 1, 0, 1)) *
                 Broadcast4(inverse_cell_);
  const QuadBits inside = (g >= Broadcast4(1)) & (g < Broadcast4(kSide - 1));
  if (!BothLanes(__builtin_shufflevector(inside, inside, 0, 1) &
                 __builtin_shufflevector(inside, inside, 2, 3))) {
    return false;
  }
  // The radius has Covered's bits, its terms being exact: c = floor(g) >= 1,
  // so f = g - c is exact (Sterbenz), and 1 - f and 1 + either are multiples
  // of g's ulp in [0, 2]. Then min(g - (c - 1), (c + 2) - g) over both axes
  // is 1 + min(f, 1 - f).
  const QuadCells c = __builtin_convertvector(g, QuadCells);
  const Quad f = g - __builtin_convertvector(c, Quad);
  const Quad rest = Broadcast4(1) - f;
  const Quad nearer = f < rest ? f : rest;
  const Quad other = __builtin_shufflevector(nearer, nearer, 1, 0, 3, 2);
  const Quad radius =
      (Broadcast4(1) + (nearer < other ? nearer : other)) * Broadcast4(cell_) - Broadcast4(slack_);
  for (int q = 0; q < 2; ++q) {
    queries[q].radius1 = radius[2 * q];
    queries[q].cell = c[2 * q + 1] * kSide + c[2 * q];
  }
  g_floats = __builtin_convertvector(g, CellFloats);
  return true;
}

SCALLOP_INLINE void NearestSearchGrid::Finish(std::span<const IndexedPosition> positions,
                                              uint32_t k, unsigned certified, uint32_t entries,
                                              NearestPoint* results,
                                              std::vector<uint32_t>& refused) const {
  for (uint32_t q = 0; q < entries; ++q) {
    if ((certified & (1u << q)) == 0) AnswerExactly(positions[k + q], k + q, results, refused);
  }
}

template <int kLanes>
SCALLOP_INLINE void NearestSearchGrid::AnswerPair(std::span<const IndexedPosition> positions,
                                                  uint32_t k, NearestPoint* results,
                                                  std::vector<uint32_t>& refused) const {
  PairQuery queries[2] = {
      {.p = &positions[k].position, .out = results + positions[k].index},
      {.p = &positions[k + 1].position, .out = results + positions[k + 1].index}};
  Floats4 g = {};
  const unsigned certified = paired_ && LocatePair(queries, g)
                                 ? FindPairsQuickly<2 * kLanes, 1>(queries, &g)
                                 : kAnswerEachAlone;
  if (certified == kAnswerEachAlone) [[unlikely]] {
    AnswerAlone(positions[k], k, results, refused);
    AnswerAlone(positions[k + 1], k + 1, results, refused);
    return;
  }
  Finish(positions, k, certified, 2, results, refused);
}

template <int kLanes>
SCALLOP_INLINE void NearestSearchGrid::AnswerEachIn(std::span<const IndexedPosition> positions,
                                                    NearestPoint* results,
                                                    std::vector<uint32_t>& refused,
                                                    const NearestSearchGrid* next) const {
  const auto count = static_cast<uint32_t>(positions.size());
  uint32_t k = 0;
  LinePrefetcher prefetcher(next);
  // Two pairs at once: each pair's pass is one chain of dependent steps, and
  // two chains side by side keep the CPU busy where one waited (three spilled
  // registers and lost a fifth). In AVX2 only: in SSE2, whose vectors hold
  // half as much, two pairs spilled and halved the speed.
  constexpr bool kTwoPairs = kLanes == 4;
  for (; kTwoPairs && k + 4 <= count; k += 4) {
    prefetcher.Step<2 * kPrefetchLinesPerPair>();
    PairQuery queries[4];
    for (int q = 0; q < 4; ++q) {
      queries[q] = {.p = &positions[k + q].position, .out = results + positions[k + q].index};
    }
    Floats4 g[2] = {};
    // Both pairs located whatever the first's verdict (each fills its queries).
    const bool first_located = LocatePair(queries, g[0]);
    const bool second_located = LocatePair(queries + 2, g[1]);
    const bool located = first_located && second_located;
    const unsigned certified =
        paired_ && located ? FindPairsQuickly<2 * kLanes, 2>(queries, g) : kAnswerEachAlone;
    if (certified == kAnswerEachAlone) [[unlikely]] {
      // A long row or a block leaving the grid in one pair: each pair alone.
      AnswerPair<kLanes>(positions, k, results, refused);
      AnswerPair<kLanes>(positions, k + 2, results, refused);
      continue;
    }
    Finish(positions, k, certified, 4, results, refused);
  }
  for (; k + 2 <= count; k += 2) {
    prefetcher.Step<kPrefetchLinesPerPair>();
    AnswerPair<kLanes>(positions, k, results, refused);
  }
  if (k < count) AnswerAlone(positions[k], k, results, refused);
}

void NearestSearchGrid::AnswerEach(std::span<const IndexedPosition> positions,
                                   std::span<NearestPoint> results, std::vector<uint32_t>& refused,
                                   const NearestSearchGrid* next) const {
  if (four_lanes_) {
    AnswerEachInFourLanes(positions, results.data(), refused, next);
  } else {
    AnswerEachInTwoLanes(positions, results.data(), refused, next);
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
                                             NearestPoint* results, std::vector<uint32_t>& refused,
                                             const NearestSearchGrid* next) const {
  AnswerEachIn<2>(positions, results, refused, next);
}

#if defined(__x86_64__) || defined(__i386__)
__attribute__((target("avx2"))) bool NearestSearchGrid::FindInBlockInFourLanes(
    const Vec2& p, int cx, int cy, double radius1, TwoNearest& best) const {
  return FindInBlockQuickly<4>(p, cx, cy, radius1, best);
}

__attribute__((target("avx2"))) void NearestSearchGrid::AnswerEachInFourLanes(
    std::span<const IndexedPosition> positions, NearestPoint* results,
    std::vector<uint32_t>& refused, const NearestSearchGrid* next) const {
  AnswerEachIn<4>(positions, results, refused, next);
}
#else
bool NearestSearchGrid::FindInBlockInFourLanes(const Vec2& p, int cx, int cy, double radius1,
                                               TwoNearest& best) const {
  return FindInBlockInTwoLanes(p, cx, cy, radius1, best);
}

void NearestSearchGrid::AnswerEachInFourLanes(std::span<const IndexedPosition> positions,
                                              NearestPoint* results, std::vector<uint32_t>& refused,
                                              const NearestSearchGrid* next) const {
  AnswerEachInTwoLanes(positions, results, refused, next);
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
