// Domain: the bounded region a sampler fills, a rectangle or the torus made by
// identifying its opposite edges. Shared by the samplers, the verifier and the
// analysis, which judge or measure points on the same domain.
#pragma once

#include "scallop/geometry/rect.h"

namespace scallop {

struct Domain {
  Rect rect;
  // Distances wrap around: x0 and x1 (y0 and y1) are the same line.
  bool torus = false;
};

}  // namespace scallop
