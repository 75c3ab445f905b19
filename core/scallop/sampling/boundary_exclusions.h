// BoundaryExclusions: a layered world's exclusion disks as A3 sees them (issue 19; docs/design.md,
// "Layered worlds"). A disk cuts the arc it covers from a candidate's circle, refuses the
// placements that fall inside it, and its own circle is a candidate of another radius: a spot
// that no point's circle reaches (a pocket that disks enclose) lies on some disk's circle.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "scallop/geometry/vec2.h"
#include "scallop/sampling/arc_bins.h"
#include "scallop/sampling/available_boundary.h"
#include "scallop/sampling/sampling_problem.h"

namespace scallop {

// A disk near a circle: the bins of the arc it covers, by a DiskBins table or from the arc
// itself, and what computing that arc takes when a bin left over needs it.
struct DiskArc {
  ArcBins bins;
  Vec2 offset;  // the disk's centre less the circle's
  double disk_radius;
  // Where the arc (CoveredArcOfCircle) was computed already, into the exact arcs; -1: not yet.
  int32_t exact;
};

// Not thread-safe: each query keeps what it found for the next calls.
class BoundaryExclusions {
 public:
  // `disks` in any order (disks of radius <= 0 exclude nothing and are dropped); each is cut with
  // the radius SpacingFor(D, max_abs_coordinate), so that placements on the cut keep D in
  // doubles, as points keep d (min_distance) on circles of radius `spacing`. O(disks) time and
  // memory, and a DiskBins table looked up for each pair of radii; nothing for no disks.
  BoundaryExclusions(std::span<const ExclusionDisk> disks, double min_distance, double spacing,
                     double max_abs_coordinate) {
    Reset(disks, min_distance, spacing, max_abs_coordinate);
  }
  // No disks, until Reset.
  BoundaryExclusions() = default;

  // As constructed anew with these arguments, in the memory this one holds (a plane engine's
  // scratch, region after region: a forest's 1,700 regions a query each allocated about ten
  // lists here).
  void Reset(std::span<const ExclusionDisk> disks, double min_distance, double spacing,
             double max_abs_coordinate);

  bool empty() const { return disks_.empty(); }
  // Disks are numbered 0 .. size() - 1 in a fixed order (by cell, then as given).
  size_t size() const { return disks_.size(); }
  Vec2 centre(size_t k) const { return disks_[k].centre; }
  // The radius disk k is cut with, a hair above its D.
  double cut_radius(size_t k) const { return disks_[k].cut; }

  // Removes from `boundary`, the available part of the circle of radius `spacing` about
  // `centre` (a point's), the arcs the disks cover, and remembers the disks near it for
  // Excludes. Leaves the very ranges that SubtractArc of every arc (CoveredArcOfCircle) would:
  // an arc is computed only if it may meet a bin the ranges meet, and the bins a disk covers
  // whole (DiskBins' table for its ratio, where it has one) are cut as they are.
  // O(disks near the circle + ranges x exact cuts).
  void CutAroundPoint(const Vec2& centre, AvailableBoundary& boundary) {
    if (GatherAroundPoint(centre)) {
      Cut(boundary);
    } else {
      boundary.Clear();
    }
  }

  // CutAroundPoint in two steps, so that the disks' whole bins can be dropped before the
  // points' arcs are cut (CandidateBoundary::Build's covered_later): first the disks near the
  // circle, remembered for the calls below and Excludes (false: one holds the whole circle)...
  bool GatherAroundPoint(const Vec2& centre) {
    StartSearch(spacing_);
    return AddDisksNear(centre, from_point_.data(), SIZE_MAX);
  }
  // ... the bins their arcs cover whole...
  uint64_t GatheredCoveredBins() const { return covered_; }
  // ... and their arcs removed from `boundary`, as CutAroundPoint removes them.
  void CutGathered(AvailableBoundary& boundary) const { Cut(boundary); }

  // The same for the circle of disk k (its cut radius), with the other disks and the disks of
  // radius `spacing` about those of `points` within reach of it.
  void CutAroundDisk(size_t k, std::span<const Vec2> points, AvailableBoundary& boundary) {
    if (GatherAroundDisk(k, points)) {
      CutGatheredDisk(k, boundary);
    } else {
      boundary.Clear();
    }
  }

  // CutAroundDisk in two steps, so that a circle the points' disks cover (9 pockets in 10 in a
  // forest) is settled before its boundary is built: first the points' arcs on disk k's circle,
  // remembered for the call below (false: their bins cover the whole circle, so nothing is left
  // of it, whatever else is cut)...
  bool GatherAroundDisk(size_t k, std::span<const Vec2> points);
  // ... then the other disks' arcs, and all the arcs removed from `boundary`.
  void CutGatheredDisk(size_t k, AvailableBoundary& boundary);

  // Whether a disk remembered by the last Cut call holds x: dx^2 + dy^2 < D^2 in doubles, the
  // verifier's expression with D as given. REQUIRES: x on (or within rounding of) that call's
  // circle.
  bool Excludes(Vec2 x) const;

  // Whether any disk holds x, as Excludes. O(disks): for a run's seed.
  bool AnyExcludes(Vec2 x) const;

 private:
  // One of the distinct radii, with the tables that see its disks: from a point's circle, and
  // (for_disk[j]) from the circle of a disk of radius j; and the table that sees a point's disk
  // from its own circle. Null where the ratio has no table.
  struct Radius {
    double given;
    double cut;
    double squared;  // given^2, as the verifier squares D
    const DiskBins* from_point;
    std::vector<const DiskBins*> from_disk;
    const DiskBins* point_from_here;
  };
  struct Disk {
    Vec2 centre;
    double cut;       // radii_[radius].cut, here for the search
    uint32_t radius;  // into radii_
  };

  // Removes the arcs of arcs_ from `boundary`, as CutAroundPoint says.
  void Cut(AvailableBoundary& boundary) const;
  // Empties arcs_ and near_ for a search about a circle of radius `circle`.
  void StartSearch(double circle);
  // Adds to arcs_ and near_ the disks (but `skip`) whose cut circle may meet the circle of the
  // search about `centre`; `tables[j]` sees radius j's disks from it. False: one holds it whole.
  bool AddDisksNear(const Vec2& centre, const DiskBins* const* tables, size_t skip);
  // AddDisksNear's search of the cells of columns c0..c1, rows r0..r1 (at most 8 of each), by
  // the occupancy bits: the disks near, into near_, in the order of their numbers.
  void GatherByOccupancy(const Vec2& centre, int64_t c0, int64_t c1, int64_t r0, int64_t r1);
  // The same by scanning each row's cells: any filing, any window.
  void GatherByRows(const Vec2& centre, int64_t c0, int64_t c1, int64_t r0, int64_t r1);
  // Appends to arcs_ the arc of the circle (radius `circle`, table scale `scale` = 16 / circle)
  // that the disk of radius `disk_radius` at `offset` covers, by `table` or exactly. False: it
  // holds the whole circle.
  bool AddArc(Vec2 offset, double scale, double disk_radius, const DiskBins* table) {
    if (table == nullptr) return AddExactArc(offset, disk_radius);
    const ArcBins bins = table->Of(offset, scale);
    covered_ |= bins.covered;
    arcs_.push_back({bins, offset, disk_radius, -1});
    return true;
  }
  // AddArc without a table: the arc computed, and its bins from its keys.
  [[gnu::noinline]] bool AddExactArc(Vec2 offset, double disk_radius);

  std::vector<Radius> radii_;
  std::vector<Disk> given_;  // as given, for the filing below (kept for its memory)
  std::vector<Disk> disks_;  // by cell, then as given
  double spacing_ = 0.0;
  double largest_cut_ = 0.0;
  // Disks filed in square cells of side largest_cut_: cell c holds disks
  // [cell_start_[c], cell_start_[c + 1]).
  Vec2 origin_;
  double inverse_cell_ = 0.0;
  int64_t columns_ = 0, rows_ = 0;
  std::vector<uint32_t> cell_start_;
  std::vector<uint32_t> cell_filled_;  // the filing's cursor a cell (kept for its memory)
  // Where no cell holds two disks (a forest's later layers: the earlier layers' points lie 2.81
  // or more apart, in cells 1.32 wide), a bit a cell saying which hold one, so that a search
  // reads the occupied cells of its window only (a forest's search reads 3.8 disks in 5.1 rows
  // of cells, and branched on each row's count). Row r's bytes start at
  // occupancy_[r * occupancy_stride_], 8 spare bytes a row and 7 spare rows of zeros: a window
  // reads 8 bytes from any column's byte, 8 rows from any row. Empty where a cell holds two or
  // more disks: the rows of cell_start_ are scanned.
  int64_t occupancy_stride_ = 0;
  std::vector<uint8_t> occupancy_;
  // With more than kCountedCells cells, and occupancy_, the disks filed before each byte of
  // occupancy_ (spare rows not): a cell's disk is then numbered from the bits alone, not read
  // from cell_start_ (on a 250k square, reading it and then the disk it names cost two cache
  // misses a disk; the bits and these counts are a sixth of its size). Fewer cells stay in
  // cache: there cell_start_ is read, in fewer instructions.
  static constexpr size_t kCountedCells = size_t{1} << 16;
  std::vector<uint32_t> filed_before_;
  std::vector<const DiskBins*> from_point_;  // radii_[j].from_point, in one array
  // What the last search found: the radius of its circle, the arcs, and the disks near it,
  // near_[0, near_count_) (room for every disk and one more, so that they are filed without a
  // branch each).
  double circle_ = 0.0;
  std::vector<DiskArc> arcs_;
  uint64_t covered_ = 0;  // the bins arcs_ cover whole (ArcBins::covered), or-ed
  std::vector<KeyArc> exact_arcs_;
  std::vector<uint32_t> near_;
  size_t near_count_ = 0;
};

}  // namespace scallop
