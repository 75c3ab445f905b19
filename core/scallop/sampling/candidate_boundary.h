// CandidateBoundary: what is left for A3 to place on of a candidate's circle
// (radius s), given its neighbours. Bins first (arc_bins.h): the bins some
// neighbour's arc covers whole are dropped at once, and only the arcs that
// meet a bin left over are computed and cut exactly. At 1M points that is
// 1.6 exact arcs a candidate of 7.5, and 3 candidates in 10 need none.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "scallop/geometry/vec2.h"
#include "scallop/sampling/arc_bins.h"
#include "scallop/sampling/available_boundary.h"
#include "scallop/sampling/boundary_arcs.h"

namespace scallop {

class CandidateBoundary {
 public:
  explicit CandidateBoundary(double spacing)
      : spacing_squared_(spacing * spacing), bins_(spacing) {}

  // Makes this what CandidateBoundary(spacing) would be, keeping its scratch
  // (for a caller that runs A3 again and again: BoundaryScratch).
  void Reset(double spacing) {
    spacing_squared_ = spacing * spacing;
    bins_ = NeighbourBins(spacing);
  }

  // Sets `boundary` to the circle of radius s about `centre` less
  // `other_arcs` (keys) and the arcs that the disks of radius s about
  // `neighbours` cover (as CoveredArcs computes them): the very ranges that
  // Reset() and then SubtractArc of every one of those arcs, in any order,
  // would leave. REQUIRES: SquaredLength(q - centre) < 4 s^2 for every
  // neighbour q, as computed in doubles. O(neighbours + ranges x exact cuts).
  //
  // `covered_later`: bins (ArcBins::covered) of arcs the caller cuts next
  // anyway (a layered world's exclusion disks): dropped with the others, so
  // that no neighbour's arc is computed for them alone. The ranges left
  // after those cuts are the same either way.
  void Build(Vec2 centre, std::span<const KeyArc> other_arcs, std::span<const Vec2> neighbours,
             AvailableBoundary& boundary, uint64_t covered_later = 0);

 private:
  double spacing_squared_;
  NeighbourBins bins_;
  // Scratch, kept between calls: the bins each neighbour's arc may meet,
  // the neighbours whose arcs are cut exactly, and those arcs.
  std::vector<uint64_t> reached_;
  std::vector<Vec2> to_cut_;
  std::vector<KeyArc> cut_arcs_;
};

// In the header, for the compiler to inline where it pays: it runs for
// every candidate.
inline void CandidateBoundary::Build(Vec2 centre, std::span<const KeyArc> other_arcs,
                                     std::span<const Vec2> neighbours, AvailableBoundary& boundary,
                                     uint64_t covered_later) {
  const size_t count = neighbours.size();
  if (reached_.size() < count) reached_.resize(count + 8);
  uint64_t covered = covered_later;
  for (const KeyArc& arc : other_arcs) covered |= BinsOf(arc).covered;
  for (size_t n = 0; n < count; ++n) {
    const ArcBins bins = bins_.Of(neighbours[n], centre);
    covered |= bins.covered;
    reached_[n] = bins.reached;
  }
  // Why this leaves the same ranges as cutting every arc: ranges are the
  // open intervals left of (0, 4), so each is determined by the set it
  // covers. The bins dropped lie inside arcs; an arc that meets no bin left
  // changes nothing; the rest are cut.
  const uint64_t left = ~covered;
  boundary.ResetToBins(left);
  if (boundary.empty()) return;
  for (const KeyArc& arc : other_arcs) {
    if ((BinsOf(arc).reached & left) != 0) boundary.SubtractArc(arc.from_key, arc.to_key);
  }
  // The neighbours to cut, gathered without a branch each (whether one is
  // cut cannot be predicted); then all their arcs, then the cuts: the
  // arcs' divisions and square roots overlap instead of each waiting for
  // the cut before it.
  if (to_cut_.size() < count) to_cut_.resize(count + 8);
  size_t cut_count = 0;
  for (size_t n = 0; n < count; ++n) {
    to_cut_[cut_count] = neighbours[n];
    cut_count += (reached_[n] & left) != 0;
  }
  if (cut_arcs_.size() < cut_count + 1) cut_arcs_.resize(cut_count + 8);
  for (size_t n = 0; n < cut_count; n += 2) {
    // An odd count computes the last arc twice, in the spare lane.
    const Vec2 second = to_cut_[std::min(n + 1, cut_count - 1)];
    CoveredArcs(to_cut_[n] - centre, second - centre, spacing_squared_, &cut_arcs_[n]);
  }
  for (size_t n = 0; n < cut_count && !boundary.empty(); ++n) {
    boundary.SubtractArc(cut_arcs_[n].from_key, cut_arcs_[n].to_key);
  }
}

}  // namespace scallop
