// CSV, JSON and SVG output of a point set.
#include "client/output/point_output.h"

#include <cmath>
#include <iomanip>
#include <nlohmann/json.hpp>

#include "scallop/plane/world_layers.h"

namespace scallop::cli {
namespace {

// Fill colours of layers 0, 1, ...: distinct at a glance, dark enough on white.
constexpr const char* kLayerColours[] = {"#1b7837", "#b35806", "#5e3c99", "#2166ac",
                                         "#b2182b", "#4d4d4d", "#01665e", "#c51b7d"};

const char* LayerColour(size_t layer) {
  return kLayerColours[layer % (sizeof(kLayerColours) / sizeof(kLayerColours[0]))];
}

void WriteCsv(std::ostream& out, std::span<const Vec2> points, std::span<const uint64_t> ids,
              std::span<const double> radii, const PointLayers& layers) {
  out << std::setprecision(17);
  const bool with_layers = !layers.of.empty();
  out << CsvHeader(!ids.empty(), !radii.empty(), with_layers);
  for (size_t i = 0; i < points.size(); ++i) {
    if (!ids.empty()) out << ids[i] << ',';
    out << points[i].x << ',' << points[i].y;
    if (with_layers) out << ',' << layers.names[layers.of[i]];
    if (!radii.empty()) out << ',' << radii[i];
    out << '\n';
  }
}

void WriteJson(std::ostream& out, std::span<const Vec2> points, std::span<const uint64_t> ids,
               std::span<const double> radii, const PointLayers& layers) {
  nlohmann::json xs = nlohmann::json::array(), ys = nlohmann::json::array();
  for (const Vec2& p : points) {
    xs.push_back(p.x);
    ys.push_back(p.y);
  }
  nlohmann::json document{{"count", points.size()}, {"x", xs}, {"y", ys}};
  if (!ids.empty()) document["id"] = std::vector<uint64_t>(ids.begin(), ids.end());
  if (!radii.empty()) document["r"] = std::vector<double>(radii.begin(), radii.end());
  if (!layers.of.empty()) {
    nlohmann::json names = nlohmann::json::array();
    for (const uint8_t layer : layers.of) names.push_back(layers.names[layer]);
    document["layer"] = names;
  }
  out << document.dump() << '\n';
}

void WriteSvg(std::ostream& out, std::span<const Vec2> points, std::span<const double> radii,
              const Rect& view, const SvgStyle& style, const PointLayers& layers) {
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
  const auto circle = [&](size_t i) {
    // A field world's disks are R/2 at each point: where they touch, the spacing is met.
    const double r = radii.empty() ? style.dot_radius : radii[i] / 2;
    out << "<circle cx=\"" << points[i].x << "\" cy=\"" << points[i].y << "\" r=\"" << r
        << "\"/>\n";
  };
  if (layers.of.empty()) {
    out << "<g fill=\"#234\">\n";
    for (size_t i = 0; i < points.size(); ++i) circle(i);
    out << "</g>\n";
  } else {
    // One group a layer, the largest drawn first (layers are numbered as given; the caller's
    // points come layer by layer), half transparent so that overlaps show.
    for (size_t layer = 0; layer < layers.names.size(); ++layer) {
      out << "<g fill=\"" << LayerColour(layer) << "\" fill-opacity=\"0.6\">\n";
      for (size_t i = 0; i < points.size(); ++i) {
        if (layers.of[i] == layer) circle(i);
      }
      out << "</g>\n";
    }
  }
  out << "</g>\n";
  if (!layers.of.empty()) {
    // The legend, upright (outside the flipped group), in the top-left corner.
    const double size = std::max(view.Width(), view.Height()) / 40.0;
    for (size_t layer = 0; layer < layers.names.size(); ++layer) {
      const double y = -view.y1 + size * (1.5 * static_cast<double>(layer) + 1.0);
      out << "<rect x=\"" << view.x0 + size / 2 << "\" y=\"" << y - size * 0.8 << "\" width=\""
          << size << "\" height=\"" << size << "\" fill=\"" << LayerColour(layer) << "\"/>\n"
          << "<text x=\"" << view.x0 + size * 2 << "\" y=\"" << y << "\" font-size=\"" << size
          << "\" font-family=\"sans-serif\">" << layers.names[layer] << "</text>\n";
    }
  }
  out << "</svg>\n";
}

}  // namespace

std::vector<double> RadiiAt(const RadiusField* field, std::span<const Vec2> points) {
  std::vector<double> radii;
  if (field == nullptr) return radii;
  radii.reserve(points.size());
  for (const Vec2& p : points) radii.push_back(field->Evaluate(p));
  return radii;
}

std::vector<double> LayerRadiiAt(const World& world, std::span<const Vec2> points,
                                 std::span<const uint8_t> layers, bool for_disks) {
  std::vector<double> radii;
  const WorldLayers* world_layers = world.layers();
  if (world_layers == nullptr) return radii;
  bool any_field = false;
  for (int k = 0; k < world_layers->count(); ++k) {
    // The spec's, not the layer world's: a later layer's world has a constant field.
    any_field = any_field || world.spec().layers[static_cast<size_t>(k)].radius_field.has_value();
  }
  if (!any_field && !for_disks) return radii;
  radii.reserve(points.size());
  for (size_t k = 0; k < points.size(); ++k) {
    radii.push_back(world_layers->world(layers[k]).SpacingAt(points[k]));
  }
  return radii;
}

std::vector<std::string> LayerNames(const World& world) {
  std::vector<std::string> names;
  if (const WorldLayers* layers = world.layers()) {
    for (int k = 0; k < layers->count(); ++k) names.push_back(layers->name(k));
  }
  return names;
}

std::string CsvHeader(bool with_ids, bool with_radii, bool with_layers) {
  return std::string(with_ids ? "id," : "") + "x,y" + (with_layers ? ",layer" : "") +
         (with_radii ? ",r" : "") + "\n";
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
                 const SvgStyle& style, const PointLayers& layers) {
  switch (format) {
    case PointFormat::kCsv:
      WriteCsv(out, points, ids, radii, layers);
      break;
    case PointFormat::kJson:
      WriteJson(out, points, ids, radii, layers);
      break;
    case PointFormat::kSvg:
      WriteSvg(out, points, radii, view, style, layers);
      break;
    case PointFormat::kNone:
      break;
  }
}

}  // namespace scallop::cli
