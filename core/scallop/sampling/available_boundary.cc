// Angular range arithmetic for A3's available boundary.
#include "scallop/sampling/available_boundary.h"

#include <cmath>

namespace scallop {

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
    SubtractNormalised(begin, end);
  } else {
    SubtractNormalised(begin, kTwoPi);
    SubtractNormalised(0.0, end - kTwoPi);
  }
}

void AvailableBoundary::SubtractNormalised(double begin, double end) {
  scratch_.clear();
  for (const Range& r : ranges_) {
    if (r.end <= begin || r.begin >= end) {
      scratch_.push_back(r);
      continue;
    }
    if (r.begin < begin) scratch_.push_back({r.begin, begin});
    if (r.end > end) scratch_.push_back({end, r.end});
  }
  ranges_.swap(scratch_);
}

double AvailableBoundary::SampleAngle(Rng& rng) const {
  double target = rng.Uniform() * TotalLength();
  for (const Range& r : ranges_) {
    const double length = r.end - r.begin;
    if (target < length) return r.begin + target;
    target -= length;
  }
  // Rounding in the running subtraction can leave target a hair past the sum.
  return ranges_.back().end - 0.5 * (ranges_.back().end - ranges_.back().begin);
}

}  // namespace scallop
