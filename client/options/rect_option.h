// Parsing of rectangle options such as --domain X0,Y0,X1,Y1.
#pragma once

#include <string>

#include "scallop/base/status.h"
#include "scallop/geometry/rect.h"

namespace scallop::cli {

// Parses "x0,y0,x1,y1" (four finite numbers, x0 < x1, y0 < y1); the error
// names `option` and says what is wrong.
StatusOr<Rect> ParseRect(const std::string& text, const std::string& option);

}  // namespace scallop::cli
