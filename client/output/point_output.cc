// CSV, JSON and SVG output of a point set.
#include "client/output/point_output.h"

#include <cmath>
#include <iomanip>
#include <nlohmann/json.hpp>

namespace scallop::cli {
namespace {

void WriteCsv(std::ostream& out, std::span<const Vec2> points, std::span<const uint64_t> ids,
              std::span<const double> radii) {
  out << std::setprecision(17);
  out << CsvHeader(!ids.empty(), !radii.empty());
  for (size_t i = 0; i < points.size(); ++i) {
    if (!ids.empty()) out << ids[i] << ',';
    out << points[i].x << ',' << points[i].y;
    if (!radii.empty()) out << ',' << radii[i];
    out << '\n';
  }
}

void WriteJson(std::ostream& out, std::span<const Vec2> points, std::span<const uint64_t> ids,
               std::span<const double> radii) {
  nlohmann::json xs = nlohmann::json::array(), ys = nlohmann::json::array();
  for (const Vec2& p : points) {
    xs.push_back(p.x);
    ys.push_back(p.y);
  }
  nlohmann::json document{{"count", points.size()}, {"x", xs}, {"y", ys}};
  if (!ids.empty()) document["id"] = std::vector<uint64_t>(ids.begin(), ids.end());
  if (!radii.empty()) document["r"] = std::vector<double>(radii.begin(), radii.end());
  out << document.dump() << '\n';
}

void WriteSvg(std::ostream& out, std::span<const Vec2> points, std::span<const double> radii,
              const Rect& view, const SvgStyle& style) {
  // y grows upwards in the world and downwards in SVG: flip with a transform.
  const double stroke = std::max(view.Width(), view.Height()) / 1000.0;
  out << std::setprecision(9);
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"" << view.x0 << ' ' << -view.y1 << ' '
      << view.Width() << ' ' << view.Height() << "\" width=\"800\" height=\""
      << 800.0 * view.Height() / view.Width() << "\">\n"
      << "<rect x=\"" << view.x0 << "\" y=\"" << -view.y1 << "\" width=\"" << view.Width()
      << "\" height=\"" << view.Height() << "\" fill=\"white\"/>\n"
      << "<g transform=\"scale(1,-1)\">\n";
  if (style.seam_spacing > 0) {
    out << "<g stroke=\"#c33\" stroke-width=\"" << stroke << "\" stroke-dasharray=\"" << 4 * stroke
        << "\">\n";
    const double s = style.seam_spacing;
    for (double x = std::ceil(view.x0 / s) * s; x <= view.x1; x += s) {
      out << "<line x1=\"" << x << "\" y1=\"" << view.y0 << "\" x2=\"" << x << "\" y2=\"" << view.y1
          << "\"/>\n";
    }
    for (double y = std::ceil(view.y0 / s) * s; y <= view.y1; y += s) {
      out << "<line x1=\"" << view.x0 << "\" y1=\"" << y << "\" x2=\"" << view.x1 << "\" y2=\"" << y
          << "\"/>\n";
    }
    out << "</g>\n";
  }
  out << "<g fill=\"#234\">\n";
  for (size_t i = 0; i < points.size(); ++i) {
    // A field world's disks are R/2 at each point: where they touch, the spacing is met.
    const double r = radii.empty() ? style.dot_radius : radii[i] / 2;
    out << "<circle cx=\"" << points[i].x << "\" cy=\"" << points[i].y << "\" r=\"" << r
        << "\"/>\n";
  }
  out << "</g>\n</g>\n</svg>\n";
}

}  // namespace

std::vector<double> RadiiAt(const RadiusField* field, std::span<const Vec2> points) {
  std::vector<double> radii;
  if (field == nullptr) return radii;
  radii.reserve(points.size());
  for (const Vec2& p : points) radii.push_back(field->Evaluate(p));
  return radii;
}

std::string CsvHeader(bool with_ids, bool with_radii) {
  return std::string(with_ids ? "id," : "") + "x,y" + (with_radii ? ",r" : "") + "\n";
}

const std::vector<std::pair<std::string, PointFormat>>& PointFormatNames() {
  static const std::vector<std::pair<std::string, PointFormat>> names{{"csv", PointFormat::kCsv},
                                                                      {"json", PointFormat::kJson},
                                                                      {"svg", PointFormat::kSvg},
                                                                      {"none", PointFormat::kNone}};
  return names;
}

void WritePoints(std::ostream& out, PointFormat format, std::span<const Vec2> points,
                 std::span<const uint64_t> ids, std::span<const double> radii, const Rect& view,
                 const SvgStyle& style) {
  switch (format) {
    case PointFormat::kCsv:
      WriteCsv(out, points, ids, radii);
      break;
    case PointFormat::kJson:
      WriteJson(out, points, ids, radii);
      break;
    case PointFormat::kSvg:
      WriteSvg(out, points, radii, view, style);
      break;
    case PointFormat::kNone:
      break;
  }
}

}  // namespace scallop::cli
