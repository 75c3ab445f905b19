// Tiles a rectangle with squares of a given side from its lower-left corner, the last column
// and row clipped to it: the base cells that the field sampler's sweep and the field verifier
// refine, visited in the same rows-from-the-bottom order.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "scallop/geometry/rect.h"

namespace scallop {

// Calls visit(Rect) for each tile, row by row from the bottom. REQUIRES: side > 0 and the tile
// count (area / side^2) reasonable; the caller bounds it. O(tiles).
template <typename Visit>
void ForEachTile(const Rect& r, double side, Visit visit) {
  const auto columns = static_cast<int64_t>(std::ceil(r.Width() / side));
  const auto rows = static_cast<int64_t>(std::ceil(r.Height() / side));
  for (int64_t j = 0; j < rows; ++j) {
    const double y0 = r.y0 + side * static_cast<double>(j);
    const double y1 = j + 1 == rows ? r.y1 : std::min(r.y1, y0 + side);
    for (int64_t i = 0; i < columns; ++i) {
      const double x0 = r.x0 + side * static_cast<double>(i);
      const double x1 = i + 1 == columns ? r.x1 : std::min(r.x1, x0 + side);
      visit(Rect{x0, y0, x1, y1});
    }
  }
}

}  // namespace scallop
