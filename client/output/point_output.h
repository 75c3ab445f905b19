// Writers for the point formats the CLI prints: CSV, JSON and SVG.
#pragma once

#include <cstdint>
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "scallop/geometry/rect.h"
#include "scallop/geometry/vec2.h"

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

// CSV `x,y` with a header, or `id,x,y` when ids are given (one per point).
// Coordinates are printed with 17 significant digits, so they read back exactly.
void WritePoints(std::ostream& out, PointFormat format, std::span<const Vec2> points,
                 std::span<const uint64_t> ids, const Rect& view, const SvgStyle& style);

}  // namespace scallop::cli
