// NearestPoint: the cellular-noise basis at one position (what NearestLookup
// answers), apart from the lookup so that a search grid can write it directly.
#pragma once

#include <cstdint>

#include "scallop/geometry/vec2.h"

namespace scallop {

// The basis at one position. "Nearest" orders points by the squared distance
// dx*dx + dy*dy computed in doubles (dx = x - point.x), ties by smaller id,
// so every replica agrees to the bit; f1 and f2 are the square roots of the
// first two (correctly rounded, hence exact functions of the points). The
// bounds on f1 and f2 hold at least 2 d inside the precision limit; nearer,
// f1 < (1 + sqrt 2) d (1 + tolerance) (docs/noise.md, "At the limit"). On a
// radius-field world read r_max for d (f1 < r_max, f1 + f2 < 2 r_max), away
// from masks: near a masked area neither is bounded (docs/noise.md,
// "Radius-field worlds").
struct NearestPoint {
  uint64_t id = 0;         // nearest point's id (point_id.h)
  Vec2 position;           // nearest point
  double f1 = 0;           // distance to it: < d (1 + tolerance) on our maximal worlds
  double f2 = 0;           // distance to the second nearest: f1 + f2 < 2 d (1 + tolerance)
  uint64_t second_id = 0;  // second nearest point's id
  double cell_value = 0;   // CellValue(id), in [0, 1)
};

}  // namespace scallop
