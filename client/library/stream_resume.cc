// StreamRemainder: the rest of the last region's row, then the rows below.
#include "stream_resume.h"

#include <algorithm>

namespace scallop::client {

std::vector<Rect> StreamRemainder(const Rect& rect, RegionKey last, double min_distance) {
  const Rect region = RegionLayout(min_distance).RegionRect(last);
  std::vector<Rect> remainder;
  // The same row, right of `last`: its regions own exactly [region.x1, ...),
  // and the row's part of `rect` is [max(y0, region.y0), min(y1, region.y1)).
  const Rect row_rest{std::max(rect.x0, region.x1), std::max(rect.y0, region.y0), rect.x1,
                      std::min(rect.y1, region.y1)};
  if (row_rest.x0 < row_rest.x1 && row_rest.y0 < row_rest.y1) remainder.push_back(row_rest);
  if (region.y1 < rect.y1) remainder.push_back({rect.x0, region.y1, rect.x1, rect.y1});
  return remainder;
}

}  // namespace scallop::client
