// Resuming a StreamPoints call that broke (its replica went away, a proxy
// cut it): the stream's chunks come one region at a time in region row, then
// column order, so what is still missing after the last chunk received is
// the rest of that region's row and the rows after it, at most two
// rectangles. Streaming them in order continues the stream exactly: no
// point missing, none twice (docs/streaming.md, "Resuming StreamPoints").
#pragma once

#include <vector>

#include "scallop/geometry/rect.h"
#include "scallop/plane/region_layout.h"

namespace scallop::client {

// The rectangles whose streams, read one after the other, give the chunks of
// a stream of `rect` that come after the chunk of region `last` (the world's
// min_distance fixes the regions: DescribeWorld's world, or the inline
// world). Empty when `last` was the rectangle's last region. O(1).
// REQUIRES: min_distance finite and > 0; `last` a region `rect` overlaps.
std::vector<Rect> StreamRemainder(const Rect& rect, RegionKey last, double min_distance);

}  // namespace scallop::client
