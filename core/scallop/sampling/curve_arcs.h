// The directions of a field candidate's curve that a neighbour's disk or a domain edge takes
// away, as key arcs of AvailableBoundary (A3's pseudo-angles): the field growth cuts them the
// way A3 cuts its circle's covered arcs. Only IEEE arithmetic and square roots, in a written
// order, so the keys' bits are the same everywhere.
#pragma once

#include <cmath>

#include "scallop/geometry/vec2.h"
#include "scallop/sampling/available_boundary.h"

namespace scallop {

// How a disk or a half-plane meets a circle about the candidate.
enum class ArcCut { kNone, kArc, kWhole };

// The directions u with |t u - offset| < m, for the circle of radius t about the candidate and
// the disk of radius m about the candidate + offset: an arc centred on the offset's direction,
// with cos(half-width) = a / |offset|, a = (t^2 + |offset|^2 - m^2) / (2 t). Its ends are along
// a offset -+ sqrt(|offset|^2 - a^2) offset', offset' = offset turned by +90 degrees. kNone when
// the circle misses the disk (or only touches it), kWhole when the disk holds the circle.
// REQUIRES: t > 0. O(1): one division, one square root, two pseudo-angles.
inline ArcCut DiskArc(Vec2 offset, double t, double m, KeyArc* arc) {
  const double o2 = offset.x * offset.x + offset.y * offset.y;
  const double a = (t * t + o2 - m * m) / (2.0 * t);
  if (a * a >= o2) return a >= 0.0 ? ArcCut::kNone : ArcCut::kWhole;
  const double h = std::sqrt(o2 - a * a);
  const Vec2 from{a * offset.x + h * offset.y, a * offset.y - h * offset.x};
  const Vec2 to{a * offset.x - h * offset.y, a * offset.y + h * offset.x};
  *arc = {PseudoAngle(from), PseudoAngle(to)};
  return ArcCut::kArc;
}

// The directions u with t (u . normal) >= distance, for a unit `normal` (the outward normal of a
// domain edge at `distance` from the candidate): the part of the circle beyond the edge, an arc
// centred on the normal with cos(half-width) = distance / t. REQUIRES: t > 0, |normal| = 1.
inline ArcCut BeyondLineArc(Vec2 normal, double distance, double t, KeyArc* arc) {
  const double c = distance / t;
  if (c >= 1.0) return ArcCut::kNone;
  if (c <= -1.0) return ArcCut::kWhole;
  const double s = std::sqrt(1.0 - c * c);
  const Vec2 from{c * normal.x + s * normal.y, c * normal.y - s * normal.x};
  const Vec2 to{c * normal.x - s * normal.y, c * normal.y + s * normal.x};
  *arc = {PseudoAngle(from), PseudoAngle(to)};
  return ArcCut::kArc;
}

// Applies a cut to the boundary.
inline void Cut(AvailableBoundary& boundary, ArcCut cut, const KeyArc& arc) {
  if (cut == ArcCut::kWhole) boundary.Clear();
  if (cut == ArcCut::kArc) boundary.SubtractArc(arc.from_key, arc.to_key);
}

// Removes the keys within `half_width` of `key` (wrapping at a whole turn). REQUIRES: key in
// [0, 4), 0 < half_width < 2.
inline void CutAroundKey(AvailableBoundary& boundary, double key, double half_width) {
  double from = key - half_width;
  double to = key + half_width;
  if (from < 0.0) from += kFullTurnKey;
  if (to >= kFullTurnKey) to -= kFullTurnKey;
  boundary.SubtractArc(from, to);
}

}  // namespace scallop
