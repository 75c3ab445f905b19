// AvailableBoundary: the part of a circle (a set of disjoint angular ranges)
// where boundary sampling (A3) may still place a point.
//
// It is built in two phases. While the neighbours' arcs are removed, ranges
// are keyed by a pseudo-angle: a monotone rational function of the direction
// (no trigonometry, exact to rounding), with each end's direction kept. Then
// Finish() turns the few surviving ends into true angles, in which points are
// drawn uniformly and each placed point's arc is removed.
#pragma once

#include <cstdint>
#include <vector>

#include "scallop/geometry/vec2.h"
#include "scallop/random/rng.h"

namespace scallop {

inline constexpr double kTwoPi = 6.283185307179586476925286766559;
inline constexpr double kFullTurnKey = 4.0;  // the pseudo-angle of a whole turn

// The "diamond angle" of a non-zero direction: 0 along +x, 1 along +y, 2
// along -x, 3 along -y, in [0, 4), increasing counterclockwise.
inline double PseudoAngle(Vec2 v) {
  if (v.y >= 0) return v.x >= 0 ? v.y / (v.x + v.y) : 1 - v.x / (v.y - v.x);
  return v.x < 0 ? 2 - v.y / (-v.x - v.y) : 3 + v.x / (v.x - v.y);
}

// Two lanes of doubles, or of their bits, in one SSE2 register (a GCC and
// Clang vector extension): each lane sees the IEEE operations it would see
// in scalar code, in the same order, so it gets the same bits.
using Doubles = double __attribute__((vector_size(16)));
using DoubleBits = int64_t __attribute__((vector_size(16)));

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

class AvailableBoundary {
 public:
  struct Range {
    double begin, end;  // begin < end; pseudo-angles before Finish(), radians after
    Vec2 begin_direction, end_direction;  // used before Finish() only
  };

  // The whole circle, in the pseudo-angle phase. O(1); keeps capacity.
  void Reset();

  bool empty() const { return ranges_.empty(); }
  const std::vector<Range>& ranges() const { return ranges_; }

  // Pseudo-angle phase: removes the arc that runs counterclockwise from
  // direction `from` to direction `to` (both non-zero). O(ranges).
  void SubtractArc(Vec2 from, Vec2 to) {
    SubtractArc(PseudoAngle(from), PseudoAngle(to), from, to);
  }
  // The same, given PseudoAngle(from) and PseudoAngle(to) (or values equal to them).
  void SubtractArc(double from_key, double to_key, Vec2 from, Vec2 to);
  // Removes everything.
  void Clear() { ranges_.clear(); }

  // Ends the pseudo-angle phase: ranges become radians in [0, 2 pi], one
  // atan2 per surviving end. Ranges that rounding made empty are dropped.
  void Finish();

  // Radian phase: removes the closed arc of angles within `half_width` of
  // `centre` (any real centre; half_width >= pi clears the circle). O(ranges).
  void Subtract(double centre, double half_width);

  // Radian phase: total length, and a uniformly distributed available angle
  // (REQUIRES: !empty()). O(ranges).
  double TotalLength() const;
  double SampleAngle(Rng& rng) const;

 private:
  // Removes [begin, end] (keys of the current phase) with the given end
  // directions for the pieces it cuts.
  void SubtractKeys(double begin, double end, Vec2 begin_direction, Vec2 end_direction);
  std::vector<Range> ranges_;
};

// Inline: they run for every neighbour of every candidate, and a call's
// overhead (four directions passed, registers saved) was a third of their cost.
inline void AvailableBoundary::SubtractArc(double begin, double end, Vec2 from, Vec2 to) {
  if (begin <= end) {
    SubtractKeys(begin, end, from, to);
  } else {
    SubtractKeys(begin, kFullTurnKey, from, {1, 0});
    SubtractKeys(0.0, end, {1, 0}, to);
  }
}

inline void AvailableBoundary::SubtractKeys(double begin, double end, Vec2 begin_direction,
                                            Vec2 end_direction) {
  // In place: most cuts touch one range, so copying every range would
  // dominate. Ranges are sorted and disjoint.
  const size_t count = ranges_.size();
  size_t first = 0;
  while (first < count && ranges_[first].end <= begin) ++first;
  if (first == count || ranges_[first].begin >= end) return;
  Range& cut = ranges_[first];
  if (cut.begin < begin && cut.end > end) {  // the cut falls inside one range: split it
    const Range right{end, cut.end, end_direction, cut.end_direction};
    cut.end = begin;
    cut.end_direction = begin_direction;
    ranges_.insert(ranges_.begin() + static_cast<std::ptrdiff_t>(first) + 1, right);
    return;
  }
  size_t erase_from = first;
  if (cut.begin < begin) {  // keep the head of the first range
    cut.end = begin;
    cut.end_direction = begin_direction;
    ++erase_from;
  }
  size_t last = erase_from;  // ranges wholly inside the cut end before `last`
  while (last < count && ranges_[last].end <= end) ++last;
  if (last < count && ranges_[last].begin < end) {  // trim the tail range
    ranges_[last].begin = end;
    ranges_[last].begin_direction = end_direction;
  }
  ranges_.erase(ranges_.begin() + static_cast<std::ptrdiff_t>(erase_from),
                ranges_.begin() + static_cast<std::ptrdiff_t>(last));
}

}  // namespace scallop
