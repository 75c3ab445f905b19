// Angular range arithmetic for A3's available boundary.
#include "scallop/sampling/available_boundary.h"

#include <cmath>

#include "scallop/base/deterministic_math.h"

namespace scallop {
void AvailableBoundary::Reset() {
  ranges_.clear();
  ranges_.push_back({0.0, kFullTurnKey, {1, 0}, {1, 0}});
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
