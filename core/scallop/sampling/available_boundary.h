// AvailableBoundary: the part of a circle (a set of disjoint angular ranges in
// [0, 2 pi)) where boundary sampling (A3) may still place a point.
#pragma once

#include <vector>

#include "scallop/random/rng.h"

namespace scallop {

inline constexpr double kTwoPi = 6.283185307179586476925286766559;

class AvailableBoundary {
 public:
  struct Range {
    double begin, end;  // begin < end, both in [0, 2 pi]
  };

  // The whole circle. O(1); keeps the capacity already allocated.
  void Reset() {
    ranges_.clear();
    ranges_.push_back({0.0, kTwoPi});
  }

  bool empty() const { return ranges_.empty(); }
  const std::vector<Range>& ranges() const { return ranges_; }
  double TotalLength() const;

  // Removes the closed arc of angles within `half_width` of `centre`
  // (any real centre; half_width >= pi clears the circle). O(ranges).
  void Subtract(double centre, double half_width);

  // A uniformly distributed available angle. REQUIRES: !empty(). O(ranges).
  double SampleAngle(Rng& rng) const;

 private:
  void SubtractNormalised(double begin, double end);  // 0 <= begin < end <= 2 pi
  std::vector<Range> ranges_;
  std::vector<Range> scratch_;
};

}  // namespace scallop
