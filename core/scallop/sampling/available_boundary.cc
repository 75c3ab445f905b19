// Angular range arithmetic for A3's available boundary.
#include "scallop/sampling/available_boundary.h"

#include <cmath>

#include "scallop/base/deterministic_math.h"

namespace scallop {
namespace {
constexpr double kFullTurnKey = 4.0;  // the pseudo-angle of a whole turn
}  // namespace

void AvailableBoundary::Reset() {
  ranges_.clear();
  ranges_.push_back({0.0, kFullTurnKey, {1, 0}, {1, 0}});
}

void AvailableBoundary::SubtractArc(double begin, double end, Vec2 from, Vec2 to) {
  if (begin <= end) {
    SubtractKeys(begin, end, from, to);
  } else {
    SubtractKeys(begin, kFullTurnKey, from, {1, 0});
    SubtractKeys(0.0, end, {1, 0}, to);
  }
}

void AvailableBoundary::SubtractKeys(double begin, double end, Vec2 begin_direction,
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

void AvailableBoundary::Finish() {
  size_t kept = 0;
  for (const Range& r : ranges_) {
    double begin = r.begin == 0.0 ? 0.0 : DetAtan2(r.begin_direction.y, r.begin_direction.x);
    double end = r.end == kFullTurnKey ? kTwoPi : DetAtan2(r.end_direction.y, r.end_direction.x);
    if (begin < 0) begin += kTwoPi;
    if (end <= 0 && r.end > 2.0) end += kTwoPi;  // the lower half-turn maps to (pi, 2 pi]
    if (begin < end) ranges_[kept++] = {begin, end, {}, {}};
  }
  ranges_.resize(kept);
}

double AvailableBoundary::TotalLength() const {
  double total = 0.0;
  for (const Range& r : ranges_) total += r.end - r.begin;
  return total;
}

void AvailableBoundary::Subtract(double centre, double half_width) {
  if (half_width <= 0.0) return;
  if (half_width >= kTwoPi / 2) {
    ranges_.clear();
    return;
  }
  double begin = centre - half_width;
  // Bring begin into [0, 2 pi); the end may then pass 2 pi and wrap.
  begin -= kTwoPi * std::floor(begin / kTwoPi);
  if (begin >= kTwoPi) begin = 0.0;
  const double end = begin + 2 * half_width;
  if (end <= kTwoPi) {
    SubtractKeys(begin, end, {}, {});
  } else {
    SubtractKeys(begin, kTwoPi, {}, {});
    SubtractKeys(0.0, end - kTwoPi, {}, {});
  }
}

double AvailableBoundary::SampleAngle(Rng& rng) const {
  double target = rng.Uniform() * TotalLength();
  for (const Range& r : ranges_) {
    const double length = r.end - r.begin;
    if (target < length) return r.begin + target;
    target -= length;
  }
  // Rounding in the running subtraction can leave target a hair past the sum.
  return ranges_.back().begin;
}

}  // namespace scallop
