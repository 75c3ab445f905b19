// Rectangle option parsing, strict: no clamping, no swapped corners.
#include "client/options/rect_option.h"

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

namespace scallop::cli {

StatusOr<std::vector<double>> ParseNumbers(const std::string& text, const std::string& option,
                                           size_t min_count, size_t max_count,
                                           const std::string& form) {
  std::vector<double> values;
  std::stringstream stream(text);
  std::string part;
  while (std::getline(stream, part, ',')) {
    char* end = nullptr;
    const double value = std::strtod(part.c_str(), &end);
    if (part.empty() || end != part.c_str() + part.size()) {
      return InvalidArgument(option + ": '" + part + "' is not a number");
    }
    if (!std::isfinite(value)) return InvalidArgument(option + ": values must be finite");
    values.push_back(value);
  }
  if (values.size() < min_count || values.size() > max_count) {
    return InvalidArgument(option + ": expected " + form);
  }
  return values;
}

StatusOr<Rect> ParseRect(const std::string& text, const std::string& option) {
  StatusOr<std::vector<double>> values = ParseNumbers(text, option, 4, 4, "X0,Y0,X1,Y1");
  if (!values.ok()) return values.status();
  const Rect rect{(*values)[0], (*values)[1], (*values)[2], (*values)[3]};
  if (!(rect.x0 < rect.x1)) return InvalidArgument(option + ": X0 must be less than X1");
  if (!(rect.y0 < rect.y1)) return InvalidArgument(option + ": Y0 must be less than Y1");
  return rect;
}

}  // namespace scallop::cli
