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
// Which pieces are dropped: a piece is a rounding artefact when its area is below
// kNegligibleAreaFraction of the starting annulus (areas are differences of antiderivatives of
// size ~outer^2, so their noise is ~1e-16 of it) AND it is thinner than kNegligibleWidthFraction
// of the outer radius at its middle angle. Area alone cannot tell noise from a real gap: the gap
// between three disks, delta outside each, has area ~5 delta^2, so an area bound at noise level
// would drop gaps up to ~1e-7 d wide and break maximality (tests/sampler_maximality_test.cc pins
// one). Such gaps are about delta wide, while a tangency sliver is noise-thin.
class ScallopedRegion {
 public:
  static constexpr double kNegligibleAreaFraction = 1e-14;
  static constexpr double kNegligibleWidthFraction = 1e-12;

  // The empty region.
  ScallopedRegion() = default;

  // The annulus inner <= |x - apex| <= outer. O(1).
  // REQUIRES: 0 < inner < outer, finite apex.
  static ScallopedRegion Annulus(Vec2 apex, double inner, double outer);
  // Makes this region the annulus inner <= |x - apex| <= outer, keeping its buffers' capacity so
  // a caller that builds many regions in turn (A1: one per new point) does not allocate. O(1).
  // REQUIRES: as Annulus.
  void Reset(Vec2 apex, double inner, double outer);
  // Makes this region a copy of `shape` with its apex moved to `apex` (sectors are apex-relative,
  // so nothing else changes), keeping this region's buffers' capacity. After
  // shape.Reset(a, inner, outer) this equals Reset(apex, inner, outer) bit for bit, without its
  // sincos and remainders. O(S) copies, no allocation once the buffers have grown.
  void AssignMoved(const ScallopedRegion& shape, Vec2 apex);

  Vec2 apex() const { return apex_; }
  const std::vector<ScallopedSector>& sectors() const { return sectors_; }
  // The cached SectorEnds of sectors()[i]: its end directions (from the operations that made
  // them, equal to UnitAt of its end angles to rounding) and its curves' remainders there, equal
  // bit for bit to SectorEnds::Of(sectors()[i], those directions). O(1). REQUIRES: i < size.
  const SectorEnds& sector_ends(size_t i) const { return sector_cache_[i].ends; }
  bool empty() const { return sectors_.empty(); }
  // Total area, cached. O(1).
  double Area() const { return area_; }
  // A radius about the apex that contains the region (never grows). O(1).
  double BoundingRadius() const { return outer_bound_; }

  // Removes the closed disk |x - centre| <= radius (absolute coordinates); the apex may lie
  // inside it. Cost: O(1) when the disk misses the bounding circle or the annulus hole; else
  // O(S) cross products and radial-bound checks, plus for each sector the disk actually reaches
  // a few sqrt and atan2/atan (one atan2 per new sector boundary, up to two atan per new sector's
  // area). Sectors the disk misses are neither copied nor moved. Allocates only when the sector
  // count grows past the capacity. REQUIRES: radius > 0, finite inputs.
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

  // Asks the processor to start loading the sector arrays, for a caller about to operate on
  // several regions whose data is cold (A1 at a million points). No effect on any result.
  void Prefetch() const;

 private:
  template <typename Operation>
  void Apply(Operation& operation);
  void Clear();
  void EraseSector(size_t index);  // from both parallel arrays

  // Per sector: its area (so Sample and Area need no recomputation), the unit directions of its
  // end angles and its curves' area remainders there (so operations need no sincos for them, and
  // neither operations nor Sample recompute those remainders) and bounds on its distances from
  // the apex (so most operations that miss it reject it with two comparisons).
  struct SectorCache {
    double area;
    SectorEnds ends;
    double min_near;  // every near distance >= this
    double max_far;   // every far distance <= this
  };

  Vec2 apex_;
  std::vector<ScallopedSector> sectors_;
  std::vector<SectorCache> sector_cache_;  // parallel to sectors_
  double area_ = 0.0;
  double outer_bound_ = 0.0;  // every far distance <= this
  double inner_bound_ = 0.0;  // every near distance >= this
  double negligible_area_ = 0.0;
};

}  // namespace scallop
