// Point files read back: CSV by lines, JSON through nlohmann-json.
#include "client/analysis/point_file.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace scallop::cli {
namespace {

// The whole field must be a number; "inf" and "nan" parse but are refused.
bool ParseFinite(const std::string& text, double* value) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  *value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && errno == 0 && std::isfinite(*value);
}

StatusOr<std::vector<Vec2>> ReadCsv(std::istream& in, const std::string& path) {
  std::string line;
  if (!std::getline(in, line)) return InvalidArgument(path + ": empty file");
  if (!line.empty() && line.back() == '\r') line.pop_back();
  // A field world's files carry r last; the points are what is analysed.
  const std::string header = line;
  const bool with_ids = header.starts_with("id,");
  const bool with_radii = header.ends_with(",r");
  if (header != "x,y" && header != "id,x,y" && header != "x,y,r" && header != "id,x,y,r") {
    return InvalidArgument(path + ": line 1: expected the header x,y, id,x,y, x,y,r or id,x,y,r");
  }
  std::vector<Vec2> points;
  for (int64_t number = 2; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    std::vector<std::string> fields;
    std::stringstream row(line);
    for (std::string field; std::getline(row, field, ',');) fields.push_back(field);
    const size_t x = with_ids ? 1 : 0;
    const size_t want = x + 2 + (with_radii ? 1 : 0);
    Vec2 p;
    if (fields.size() != want || !ParseFinite(fields[x], &p.x) ||
        !ParseFinite(fields[x + 1], &p.y)) {
      return InvalidArgument(path + ": line " + std::to_string(number) + ": expected " + header +
                             " with finite x and y");
    }
    points.push_back(p);
  }
  return points;
}

StatusOr<std::vector<Vec2>> ReadJson(std::istream& in, const std::string& path) {
  const nlohmann::json document = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (document.is_discarded() || !document.is_object()) {
    return InvalidArgument(path + ": not a JSON object");
  }
  auto xs = document.find("x"), ys = document.find("y");
  if (xs == document.end() || ys == document.end() || !xs->is_array() || !ys->is_array() ||
      xs->size() != ys->size()) {
    return InvalidArgument(path + ": expected arrays \"x\" and \"y\" of equal length");
  }
  std::vector<Vec2> points;
  for (size_t i = 0; i < xs->size(); ++i) {
    const nlohmann::json &x = (*xs)[i], &y = (*ys)[i];
    if (!x.is_number() || !y.is_number() || !std::isfinite(x.get<double>()) ||
        !std::isfinite(y.get<double>())) {
      return InvalidArgument(path + ": x[" + std::to_string(i) + "], y[" + std::to_string(i) +
                             "]: must be finite numbers");
    }
    points.push_back({x.get<double>(), y.get<double>()});
  }
  return points;
}

}  // namespace

StatusOr<std::vector<Vec2>> ReadPointFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) return InvalidArgument(path + ": cannot open");
  in >> std::ws;
  StatusOr<std::vector<Vec2>> points = in.peek() == '{' ? ReadJson(in, path) : ReadCsv(in, path);
  if (points.ok() && points->empty()) return InvalidArgument(path + ": holds no point");
  return points;
}

}  // namespace scallop::cli
