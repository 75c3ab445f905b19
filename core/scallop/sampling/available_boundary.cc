// Range arithmetic and drawing for A3's available boundary.
#include "scallop/sampling/available_boundary.h"

#include <algorithm>
#include <bit>

namespace scallop {

void AvailableBoundary::Grow(size_t count) {
  const size_t size = std::max(count, 2 * spare_.size());
  ranges_.resize(size);
  spare_.resize(size);
}

void AvailableBoundary::ResetToBins(uint64_t bins) {
  constexpr size_t kMostRuns = 32;  // of 64 bits
  if (ranges_.size() < kMostRuns + 2) Grow(kMostRuns + 2);
  count_ = 0;
  while (bins != 0) {
    // Adding the lowest set bit carries through the lowest run and clears it.
    const uint64_t run = bins & ~(bins + (bins & -bins));
    bins &= ~run;
    ranges_[count_++] = {std::countr_zero(run) / kBinsPerKey,
                         (64 - std::countl_zero(run)) / kBinsPerKey};
  }
}

double AvailableBoundary::TotalLength() const {
  double total = 0.0;
  for (const Range& r : ranges()) total += r.end - r.begin;
  return total;
}

double AvailableBoundary::SampleKey(Rng& rng, double total) const {
  double target = rng.Uniform() * total;
  for (const Range& r : ranges()) {
    const double length = r.end - r.begin;
    if (target < length) return r.begin + target;
    target -= length;
  }
  // Rounding in the running subtraction can leave target a hair past the sum.
  return ranges_[count_ - 1].begin;
}

AvailableBoundary::Draw AvailableBoundary::SampleDirection(Rng& rng) const {
  // The ranges do not change between tries, so neither does their total: summed once, in the
  // same order as each try summed it before, so the same bits.
  const double total = TotalLength();
  while (true) {
    const double key = SampleKey(rng, total);
    const Vec2 direction = DirectionAtKey(key);
    if (rng.Uniform() * (2.0 * SquaredLength(direction)) < 1.0) return {direction, key};
  }
}

}  // namespace scallop
