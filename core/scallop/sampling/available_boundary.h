// AvailableBoundary: the part of a circle (a set of disjoint angular ranges)
// where boundary sampling (A3) may still place a point.
//
// Ranges are keyed by a pseudo-angle: a monotone rational function of the
// direction, exact to rounding and free of trigonometry. Removing an arc
// takes the keys of its two end directions; a point is drawn uniformly by
// angle by drawing a key uniformly and correcting the density by rejection.
// No sine, cosine or arctangent is evaluated, so A3's bits rest on IEEE
// +, -, *, / and sqrt alone.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "scallop/geometry/double_lanes.h"
#include "scallop/geometry/vec2.h"
#include "scallop/random/rng.h"

namespace scallop {

inline constexpr double kFullTurnKey = 4.0;  // the pseudo-angle of a whole turn

// The key circle in 64 bins: bin k holds keys k / 16 to (k + 1) / 16, bounds
// exact in binary, so a key's bin is floor(16 key) without rounding.
inline constexpr double kBinsPerKey = 16.0;

// The "diamond angle" of a non-zero direction: 0 along +x, 1 along +y, 2
// along -x, 3 along -y, in [0, 4), increasing counterclockwise.
inline double PseudoAngle(Vec2 v) {
  if (v.y >= 0) return v.x >= 0 ? v.y / (v.x + v.y) : 1 - v.x / (v.y - v.x);
  return v.x < 0 ? 2 - v.y / (-v.x - v.y) : 3 + v.x / (v.x - v.y);
}

// A direction whose PseudoAngle is `key` (to rounding), for key in [0, 4]:
// in quadrant n = floor(key) it is (1 - q, q), q = key - n, turned by n right
// angles, so |x| + |y| = 1. Without a branch on the quadrant (a drawn key's
// quadrant cannot be predicted).
inline Vec2 DirectionAtKey(double key) {
  static constexpr double kSignOfX[5] = {1, -1, -1, 1, 1}, kSignOfY[5] = {1, 1, -1, -1, 1};
  const auto quadrant = static_cast<int>(key);  // key >= 0: truncation is floor
  const double q = key - quadrant;              // exact
  const double parts[2] = {1.0 - q, q};
  const int odd = quadrant & 1;  // odd quadrants swap the parts
  return {kSignOfX[quadrant] * parts[odd], kSignOfY[quadrant] * parts[odd ^ 1]};
}

// PseudoAngle of the two directions (x[i], y[i]), without branches: A3 takes
// the pseudo-angles of both ends of every neighbour's arc, whose quadrants a
// branch predictor cannot guess, and two at a time halves the divisions.
// The same values as PseudoAngle, except that a -0 comes out +0 (keys are
// only compared, and -0 == +0). In the lower half the upper half's forms
// apply to (u, w) = -(x, y); then with s = u when forward (x >= 0 above,
// x < 0 below) and s = -u when not: numerator w or s, denominator w + s,
// base 0 or 1, plus 2 below. As negation, a + (-b) = a - b, a + b = b + a
// and (-a) / b = -(a / b) are exact, each quadrant gets the bits of
// PseudoAngle's own expression.
inline Doubles PseudoAngles(Doubles x, Doubles y) {
  const Doubles zero = {0.0, 0.0}, one = {1.0, 1.0}, two = {2.0, 2.0};
  const DoubleBits sign = {INT64_MIN, INT64_MIN};
  const DoubleBits lower = y < zero;  // all ones where true
  const DoubleBits backward = (x < zero) ^ lower;
  const DoubleBits u = reinterpret_cast<DoubleBits>(x) ^ (lower & sign);
  const DoubleBits w = reinterpret_cast<DoubleBits>(y) ^ (lower & sign);
  const DoubleBits s = u ^ (backward & sign);
  const Doubles numerator = reinterpret_cast<Doubles>((w & ~backward) | (s & backward));
  const Doubles denominator = reinterpret_cast<Doubles>(w) + reinterpret_cast<Doubles>(s);
  // 0, 1, 2 or 3, exactly.
  const Doubles base = reinterpret_cast<Doubles>(lower & reinterpret_cast<DoubleBits>(two)) +
                       reinterpret_cast<Doubles>(backward & reinterpret_cast<DoubleBits>(one));
  return base + numerator / denominator;
}

// A closed arc as the keys of its ends, counterclockwise from from_key to
// to_key; from_key > to_key when it passes key 0.
struct KeyArc {
  double from_key, to_key;
};

class AvailableBoundary {
 public:
  struct Range {
    double begin, end;  // pseudo-angles, begin < end
  };

  // The whole circle. O(1); keeps capacity.
  void Reset() {
    ranges_[0] = {0.0, kFullTurnKey};
    count_ = 1;
  }

  bool empty() const { return count_ == 0; }
  std::span<const Range> ranges() const { return {ranges_.data(), count_}; }

  // Removes the closed arc that runs counterclockwise from direction `from`
  // to direction `to` (both non-zero). O(ranges).
  void SubtractArc(Vec2 from, Vec2 to) { SubtractArc(PseudoAngle(from), PseudoAngle(to)); }
  // The same, given PseudoAngle(from) and PseudoAngle(to) (or values equal to them).
  void SubtractArc(double from_key, double to_key);
  // Removes everything.
  void Clear() { count_ = 0; }

  // The bins set in `bins` (bit k: bin k), a range to each run of bins: with
  // all bits set, the whole circle. O(runs).
  void ResetToBins(uint64_t bins);

  // The bins (bit k: bin k) whose inside some range meets. O(ranges).
  uint64_t BinsMet() const {
    uint64_t bins = 0;
    for (const Range& r : ranges()) {
      // Range (b, e) meets bin k when b < (k + 1) / 16 and k / 16 < e: from the bin of b to
      // the bin below e's bound (keys are below 4 but e, which may be 4: bin 63).
      const int first = static_cast<int>(r.begin * kBinsPerKey);
      const int last = static_cast<int>(std::ceil(r.end * kBinsPerKey)) - 1;
      bins |= (~uint64_t{0} << first) & ((uint64_t{2} << last) - 1);
    }
    return bins;
  }

  // A direction drawn uniformly by angle from the available part, with its
  // key; |direction.x| + |direction.y| = 1. REQUIRES: !empty(). O(ranges)
  // per try, 4 / pi tries on average: a key drawn uniformly has angle
  // density |direction|^2 (between 1/2 and 1, the key's rate of change), so
  // it is kept with probability 1 / (2 |direction|^2).
  struct Draw {
    Vec2 direction;
    double key;
  };
  Draw SampleDirection(Rng& rng) const;

 private:
  // Removes the closed key interval [begin, end], 0 <= begin <= end <= 4.
  void SubtractKeys(double begin, double end);
  // The ranges' total length, summed in their order.
  double TotalLength() const;
  // A key drawn uniformly from the ranges, given their TotalLength().
  double SampleKey(Rng& rng, double total) const;
  // Room for `count` ranges in both buffers. Rare: the sizes only grow.
  [[gnu::noinline]] void Grow(size_t count);

  // ranges_[0, count_): sorted and disjoint. A cut writes its result into
  // spare_ and swaps; both hold at least count_ + 2 ranges.
  std::vector<Range> ranges_ = std::vector<Range>(8), spare_ = std::vector<Range>(8);
  size_t count_ = 0;
};

// Inline: it runs for every neighbour of every candidate, and a call's
// overhead was a third of its cost.
inline void AvailableBoundary::SubtractArc(double begin, double end) {
  if (begin <= end) {
    SubtractKeys(begin, end);
  } else {
    SubtractKeys(begin, kFullTurnKey);
    SubtractKeys(0.0, end);
  }
}

inline void AvailableBoundary::SubtractKeys(double begin, double end) {
  // Removing [begin, end] from a range (b, e), b < e, leaves (b, min(e, begin))
  // when b < begin and (max(b, end), e) when end < e. Every range is cut so,
  // with no branch on how the cut meets it: cuts fall anywhere, and those
  // branches were A3's costliest mispredictions. Both pieces are written;
  // the count moves past the non-empty ones (at most one more than before).
  if (spare_.size() < count_ + 2) Grow(count_ + 2);
  Range* out = spare_.data();
  size_t kept = 0;
  for (size_t r = 0; r < count_; ++r) {
    const Range range = ranges_[r];
    out[kept] = {range.begin, std::min(range.end, begin)};
    kept += range.begin < begin;
    out[kept] = {std::max(range.begin, end), range.end};
    kept += end < range.end;
  }
  ranges_.swap(spare_);
  count_ = kept;
}

}  // namespace scallop
