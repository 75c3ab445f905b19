// Checks shared by the tests of arc bins (A3's candidate_boundary_test, the field's
// field_arc_bins_test): whether bins claimed for an arc hold for its computed keys, keys drawn at
// the awkward places, and whether two boundaries are the same ranges to the bit.
#pragma once

#include <cmath>

#include "scallop/random/rng.h"
#include "scallop/sampling/arc_bins.h"
#include "scallop/sampling/available_boundary.h"

namespace scallop::arc_bin_checks {

// Whether the closed arc holds the whole closed key interval [lo, hi].
inline bool ArcHolds(const KeyArc& arc, double lo, double hi) {
  if (arc.from_key <= arc.to_key) return arc.from_key <= lo && hi <= arc.to_key;
  return arc.from_key <= lo || hi <= arc.to_key;  // passes key 0; hi <= 4
}

// Whether the closed arc meets the open key interval (lo, hi). (An arc that
// only touches a bin's bound cannot change a range: the range beyond that
// bound either runs on into the next bin, which the arc then meets, or ends
// there, open.)
inline bool ArcMeets(const KeyArc& arc, double lo, double hi) {
  if (arc.from_key <= arc.to_key) return arc.from_key < hi && lo < arc.to_key;
  return arc.from_key < hi || lo < arc.to_key;
}

// How many bins `bins` gets wrong for `arc`: covered bins the arc does not
// hold whole, and bins whose inside it meets that are not marked reached.
inline int BinErrors(const KeyArc& arc, const ArcBins& bins) {
  int errors = 0;
  for (int k = 0; k < 64; ++k) {
    const double lo = k / kBinsPerKey, hi = (k + 1) / kBinsPerKey;
    const bool covered = (bins.covered >> k) & 1, reached = (bins.reached >> k) & 1;
    if (covered && !ArcHolds(arc, lo, hi)) ++errors;
    if (!reached && ArcMeets(arc, lo, hi)) ++errors;
  }
  return errors;
}

// Keys drawn to hit the awkward places often: bin bounds, 0 and 4.
inline double AwkwardKey(Rng& rng) {
  const double u = rng.Uniform();
  if (u < 0.3) return static_cast<double>(rng.Below(65)) / kBinsPerKey;  // a bin bound
  if (u < 0.4) return std::nextafter(static_cast<double>(rng.Below(64) + 1) / kBinsPerKey, 0.0);
  return rng.Uniform(0.0, kFullTurnKey);
}

inline bool SameRanges(const AvailableBoundary& a, const AvailableBoundary& b) {
  if (a.ranges().size() != b.ranges().size()) return false;
  for (size_t r = 0; r < a.ranges().size(); ++r) {
    if (a.ranges()[r].begin != b.ranges()[r].begin || a.ranges()[r].end != b.ranges()[r].end) {
      return false;
    }
  }
  return true;
}

}  // namespace scallop::arc_bin_checks
