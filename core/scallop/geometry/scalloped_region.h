// ScallopedRegion: a disjoint union of scalloped sectors sharing one apex, with the set
// operations A1 needs (subtract / intersect a disk, clip to a half-plane) and uniform sampling.
// This is the available neighbourhood N_p of Dunbar & Humphreys 2006.
#pragma once

#include <vector>

#include "scallop/geometry/scalloped_sector.h"
#include "scallop/geometry/vec2.h"

namespace scallop {

// Sector angles lie in [-pi, pi]; the annulus starts as two half-annuli [-pi, 0] and [0, pi] so
// that every sector is at most pi wide (lines then stay on one side of the apex). Operations
// split sectors at critical angles and merge neighbouring pieces with identical curves, so the
// sector count stays small (a handful per subtracted disk that cuts the region).
//
// Pieces with area below kNegligibleAreaFraction of the starting annulus are dropped: areas are
// differences of antiderivatives of size ~outer^2, so their rounding error is ~1e-16 of the
// annulus area; pieces a hundred times smaller than that noise are tangency slivers that carry
// no probability mass a sampler could ever detect, and keeping them would only cost time.
class ScallopedRegion {
 public:
  static constexpr double kNegligibleAreaFraction = 1e-14;

  // The empty region.
  ScallopedRegion() = default;

  // The annulus inner <= |x - apex| <= outer. O(1).
  // REQUIRES: 0 < inner < outer, finite apex.
  static ScallopedRegion Annulus(Vec2 apex, double inner, double outer);

  Vec2 apex() const { return apex_; }
  const std::vector<ScallopedSector>& sectors() const { return sectors_; }
  bool empty() const { return sectors_.empty(); }
  // Total area, cached. O(1).
  double Area() const { return area_; }
  // A radius about the apex that contains the region (never grows). O(1).
  double BoundingRadius() const { return outer_bound_; }

  // Removes the closed disk |x - centre| <= radius (absolute coordinates); the apex may lie
  // inside it. Cost: O(1) when the disk misses the bounding circle or the annulus hole; else
  // O(S) in the sector count, with a few atan2/atan and sqrt per sector the disk's wedge meets
  // (about 1 us per cutting call on an A1 neighbourhood of ~5 sectors, -O3 on the 2-core dev
  // machine). No allocation once the internal buffers have grown. REQUIRES: radius > 0, finite
  // inputs.
  void SubtractDisk(Vec2 centre, double radius);

  // Keeps only the part inside the disk |x - centre| <= radius. Cost as SubtractDisk.
  // REQUIRES: radius > 0, finite inputs.
  void IntersectDisk(Vec2 centre, double radius);

  // Keeps {x : Dot(unit_normal, x) <= offset} (absolute coordinates); the apex may lie on either
  // side or on the line. O(1) when the line misses the bounding circle, else O(S).
  // REQUIRES: |unit_normal| = 1 to rounding, finite inputs.
  void IntersectHalfPlane(Vec2 unit_normal, double offset);

  // A uniformly distributed point of the region (absolute coordinates) from u0, u1, u2 in [0, 1):
  // u0 picks a sector with probability proportional to its area, (u1, u2) place the point in it
  // (ScallopedSector::Sample). Cost O(S) scan plus one AngleAtArea. REQUIRES: !empty().
  Vec2 Sample(double u0, double u1, double u2) const;

  // True when p (absolute) lies in some sector (closed). Cost: one atan2 plus O(S).
  bool Contains(Vec2 p) const;

 private:
  template <typename Operation>
  void Apply(const Operation& operation);
  void Clear();

  // Per sector: its area (so Sample and Area need no recomputation) and the unit directions of
  // its end angles (so operations need no sincos for them).
  struct SectorCache {
    double area;
    Vec2 begin_direction;
    Vec2 end_direction;
  };

  Vec2 apex_;
  std::vector<ScallopedSector> sectors_;
  std::vector<SectorCache> sector_cache_;  // parallel to sectors_
  double area_ = 0.0;
  double outer_bound_ = 0.0;  // every far distance <= this
  double inner_bound_ = 0.0;  // every near distance >= this
  double negligible_area_ = 0.0;
  // Double buffers reused across operations so the common path does not allocate.
  std::vector<ScallopedSector> scratch_sectors_;
  std::vector<SectorCache> scratch_cache_;
};

}  // namespace scallop
