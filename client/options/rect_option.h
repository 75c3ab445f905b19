// Parsing of rectangle options such as --domain X0,Y0,X1,Y1, and of the comma-separated number
// lists other options take (--radius-noise, --raster-origin).
#pragma once

#include <string>
#include <vector>

#include "scallop/base/status.h"
#include "scallop/geometry/rect.h"

namespace scallop::cli {

// Parses "x0,y0,x1,y1" (four finite numbers, x0 < x1, y0 < y1); the error
// names `option` and says what is wrong.
StatusOr<Rect> ParseRect(const std::string& text, const std::string& option);

// Parses "a,b,..." into `min_count`..`max_count` finite numbers; the error names `option`, says
// what is wrong and shows `form` ("X0,Y0,X1,Y1") when the count is off.
StatusOr<std::vector<double>> ParseNumbers(const std::string& text, const std::string& option,
                                           size_t min_count, size_t max_count,
                                           const std::string& form);

}  // namespace scallop::cli
