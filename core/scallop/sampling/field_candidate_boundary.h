// FieldCandidateBoundary: a field candidate's circle (radius t = R(p)) less the arcs its
// neighbours' disks cover (DiskArc), built by bins as A3's CandidateBoundary is: the bins some
// arc covers whole (FieldArcBins, by table) are dropped at once, and only the arcs that may meet
// a bin left are computed and cut.
#pragma once

#include <cstdint>
#include <vector>

#include "scallop/geometry/vec2.h"
#include "scallop/sampling/available_boundary.h"
#include "scallop/sampling/curve_arcs.h"
#include "scallop/sampling/field_arc_bins.h"

namespace scallop {

class FieldCandidateBoundary {
 public:
  // Starts a candidate whose circle has radius t. O(1).
  void Start(double t) {
    t_ = t;
    bins_ = FieldArcBins(t);
    covered_ = 0;
    disks_.clear();
  }

  // A neighbour's disk of radius m >= t about the candidate + offset. Returns true once the
  // disks added cover every bin: then nothing is left, and more disks change nothing.
  // REQUIRES: SquaredLength(offset) < (t + m)^2 as computed, offset not zero. O(1).
  bool Add(Vec2 offset, double m) {
    const ArcBins arc = bins_.Of(offset, m / t_);
    covered_ |= arc.covered;
    disks_.push_back({offset, m, arc.reached});
    return covered_ == ~uint64_t{0};
  }

  // Sets `boundary` to the circle less the arcs DiskArc(offset, t, m) of every disk added: the
  // very ranges that Reset() and SubtractArc of each of those arcs, in any order, would leave.
  // Ranges are the open intervals left of (0, 4), so each is fixed by the set it covers; the
  // bins dropped lie inside arcs, an arc that meets no bin left changes nothing, and the rest
  // are cut. O(disks + ranges x exact cuts).
  void Finish(AvailableBoundary& boundary) const {
    const uint64_t left = ~covered_;
    boundary.ResetToBins(left);
    for (size_t k = 0; k < disks_.size() && !boundary.empty(); ++k) {
      if ((disks_[k].reached & left) == 0) continue;
      KeyArc arc;
      Cut(boundary, DiskArc(disks_[k].offset, t_, disks_[k].m, &arc), arc);
    }
  }

 private:
  struct Disk {
    Vec2 offset;
    double m;
    uint64_t reached;
  };
  double t_ = 1.0;
  FieldArcBins bins_{1.0};
  uint64_t covered_ = 0;
  std::vector<Disk> disks_;
};

}  // namespace scallop
