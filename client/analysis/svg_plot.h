// Line plots as SVG, for `scallop analyze`: panels stacked vertically, each
// with axes, ticks, labels, one polyline per series and a legend.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace scallop::cli {

struct PlotSeries {
  std::string name;
  std::vector<double> x, y;  // equally long; non-finite y values break the line
};

struct PlotPanel {
  std::string title, x_label, y_label;
  std::vector<PlotSeries> series;
  // Horizontal dashed reference lines, (y, label), e.g. white noise's level.
  std::vector<std::pair<double, std::string>> references;
};

// Writes the panels, 640 x 280 px each, into one SVG document. Axis ranges
// cover every finite value and reference, widened to round tick steps (1, 2
// or 5 times a power of ten). Series get colours from a fixed palette, in
// order. O(total points). Text is escaped, so names may hold any characters.
void WriteSvgPanels(std::ostream& out, const std::vector<PlotPanel>& panels);

}  // namespace scallop::cli
