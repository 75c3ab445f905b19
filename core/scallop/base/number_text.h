// Numbers in messages, printed so that they read back to the same double:
// an error must show the value the caller sent, not std::to_string's six
// decimals (which print 1e-300 as 0.000000).
#pragma once

#include <charconv>
#include <string>

namespace scallop {

// The shortest text that parses back to exactly `value` ("2.0000001",
// "1e-300", "inf", "nan").
inline std::string NumberText(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

}  // namespace scallop
