// Writers for the point formats the CLI prints: CSV, JSON and SVG.
#pragma once

#include <cstdint>
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "scallop/field/radius_field.h"
#include "scallop/geometry/rect.h"
#include "scallop/geometry/vec2.h"
#include "scallop/plane/world.h"

namespace scallop::cli {

enum class PointFormat { kCsv, kJson, kSvg, kNone };

// The formats by name, for --format: "csv", "json", "svg", "none".
const std::vector<std::pair<std::string, PointFormat>>& PointFormatNames();

struct SvgStyle {
  // Draw dashed lines at multiples of this spacing (region seams); 0 for none.
  double seam_spacing = 0.0;
  // Radius of each dot, in world units (d / 2 shows the Poisson disks touching).
  double dot_radius = 0.5;
};

// A layered world's layer of each point (`of[k]` for point k), and the layers' names.
struct PointLayers {
  std::span<const uint8_t> of;
  std::span<const std::string> names;
};

// CSV `x,y` with a header, `id,x,y` when ids are given (one per point), and a last column `r`
// when radii are given (a field world: R at each point). JSON has arrays x, y, id and r the same
// way. SVG draws each point as a disk of radius r/2 when radii are given, else style.dot_radius.
// Numbers are printed with 17 significant digits, so they read back exactly.
// With `layers` (a layered world): CSV `id,x,y,layer` (the layer's name) before `r`, JSON an
// array `layer` of names, and SVG one colour a layer (a legend in the corner).
void WritePoints(std::ostream& out, PointFormat format, std::span<const Vec2> points,
                 std::span<const uint64_t> ids, std::span<const double> radii, const Rect& view,
                 const SvgStyle& style, const PointLayers& layers = {});

// R at each point for a field (the r column); empty for null (a world without a field).
std::vector<double> RadiiAt(const RadiusField* field, std::span<const Vec2> points);

// A layered world's points: each point's spacing in its layer (d, or R there), for the `r`
// column when some layer has a field, and always for SVG's disks (`for_disks`); else empty.
std::vector<double> LayerRadiiAt(const World& world, std::span<const Vec2> points,
                                 std::span<const uint8_t> layers, bool for_disks);

// A layered world's layer names, in the layers' order; empty for other worlds.
std::vector<std::string> LayerNames(const World& world);

// The CSV header line WritePoints writes, newline included: "id,x,y,layer,r\n" and its shorter
// forms.
std::string CsvHeader(bool with_ids, bool with_radii, bool with_layers = false);

}  // namespace scallop::cli
