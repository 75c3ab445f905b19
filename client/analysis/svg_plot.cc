// SVG line plots (see svg_plot.h): nice tick steps, a flipped y axis
// per panel, and a polyline per run of finite values.
#include "client/analysis/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace scallop::cli {
namespace {

constexpr double kWidth = 640, kPanelHeight = 280;
constexpr double kLeft = 64, kRight = 16, kTop = 28, kBottom = 44;
// Colour-blind safe (Okabe & Ito 2008), in the order series are given.
constexpr const char* kPalette[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                    "#E69F00", "#56B4E9", "#000000", "#F0E442"};

std::string Escape(const std::string& text) {
  std::string escaped;
  for (char c : text) {
    switch (c) {
      case '<':
        escaped += "&lt;";
        break;
      case '>':
        escaped += "&gt;";
        break;
      case '&':
        escaped += "&amp;";
        break;
      case '"':
        escaped += "&quot;";
        break;
      default:
        escaped += c;
    }
  }
  return escaped;
}

// A tick step of 1, 2 or 5 times a power of ten giving at most ~6 ticks.
double TickStep(double span) {
  const double raw = span / 6;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (double factor : {1.0, 2.0, 5.0, 10.0}) {
    if (factor * power >= raw) return factor * power;
  }
  return 10 * power;
}

struct Axis {
  double low, high, step;
};

Axis NiceAxis(double low, double high) {
  if (!(low < high)) {  // one value, or none: a unit range around it
    const double centre = std::isfinite(low) ? low : 0.0;
    low = centre - 0.5;
    high = centre + 0.5;
  }
  const double step = TickStep(high - low);
  return {std::floor(low / step) * step, std::ceil(high / step) * step, step};
}

void WritePanel(std::ostream& out, const PlotPanel& panel, double top) {
  double x_low = std::numeric_limits<double>::infinity(), x_high = -x_low;
  double y_low = x_low, y_high = -x_low;
  for (const PlotSeries& series : panel.series) {
    for (size_t i = 0; i < series.x.size() && i < series.y.size(); ++i) {
      if (!std::isfinite(series.x[i]) || !std::isfinite(series.y[i])) continue;
      x_low = std::min(x_low, series.x[i]), x_high = std::max(x_high, series.x[i]);
      y_low = std::min(y_low, series.y[i]), y_high = std::max(y_high, series.y[i]);
    }
  }
  for (const auto& [y, label] : panel.references) {
    y_low = std::min(y_low, y), y_high = std::max(y_high, y);
  }
  const Axis x_axis = NiceAxis(x_low, x_high), y_axis = NiceAxis(y_low, y_high);
  const double plot_width = kWidth - kLeft - kRight, plot_height = kPanelHeight - kTop - kBottom;
  auto px = [&](double x) {
    return kLeft + (x - x_axis.low) / (x_axis.high - x_axis.low) * plot_width;
  };
  auto py = [&](double y) {
    return top + kTop + (y_axis.high - y) / (y_axis.high - y_axis.low) * plot_height;
  };

  out << "<text x=\"" << kWidth / 2 << "\" y=\"" << top + 18
      << "\" text-anchor=\"middle\" font-weight=\"bold\">" << Escape(panel.title) << "</text>\n";
  // Grid and ticks; the count of steps is rounded so rounding never adds one.
  const int x_steps = static_cast<int>(std::lround((x_axis.high - x_axis.low) / x_axis.step));
  const int y_steps = static_cast<int>(std::lround((y_axis.high - y_axis.low) / y_axis.step));
  out << "<g stroke=\"#ddd\">\n";
  for (int i = 0; i <= x_steps; ++i) {
    const double x = px(x_axis.low + i * x_axis.step);
    out << "<line x1=\"" << x << "\" y1=\"" << py(y_axis.low) << "\" x2=\"" << x << "\" y2=\""
        << py(y_axis.high) << "\"/>\n";
  }
  for (int i = 0; i <= y_steps; ++i) {
    const double y = py(y_axis.low + i * y_axis.step);
    out << "<line x1=\"" << kLeft << "\" y1=\"" << y << "\" x2=\"" << kLeft + plot_width
        << "\" y2=\"" << y << "\"/>\n";
  }
  out << "</g>\n<g font-size=\"11\">\n";
  for (int i = 0; i <= x_steps; ++i) {
    const double value = x_axis.low + i * x_axis.step;
    out << "<text x=\"" << px(value) << "\" y=\"" << py(y_axis.low) + 14
        << "\" text-anchor=\"middle\">" << std::setprecision(4) << value << "</text>\n";
  }
  for (int i = 0; i <= y_steps; ++i) {
    const double value = y_axis.low + i * y_axis.step;
    out << "<text x=\"" << kLeft - 4 << "\" y=\"" << py(value) + 4 << "\" text-anchor=\"end\">"
        << std::setprecision(4) << value << "</text>\n";
  }
  out << "</g>\n";
  out << std::setprecision(6);
  out << "<text x=\"" << kLeft + plot_width / 2 << "\" y=\"" << top + kPanelHeight - 8
      << "\" text-anchor=\"middle\">" << Escape(panel.x_label) << "</text>\n";
  out << "<text transform=\"translate(14," << top + kTop + plot_height / 2
      << ") rotate(-90)\" text-anchor=\"middle\">" << Escape(panel.y_label) << "</text>\n";
  out << "<rect x=\"" << kLeft << "\" y=\"" << top + kTop << "\" width=\"" << plot_width
      << "\" height=\"" << plot_height << "\" fill=\"none\" stroke=\"#333\"/>\n";

  for (const auto& [y, label] : panel.references) {
    out << "<line x1=\"" << kLeft << "\" y1=\"" << py(y) << "\" x2=\"" << kLeft + plot_width
        << "\" y2=\"" << py(y) << "\" stroke=\"#888\" stroke-dasharray=\"6 4\"/>\n"
        << "<text x=\"" << kLeft + 6 << "\" y=\"" << py(y) + 13
        << "\" font-size=\"11\" fill=\"#444\">" << Escape(label) << "</text>\n";
  }
  // The legend's box, so curves passing under it stay readable.
  out << "<rect x=\"" << kLeft + plot_width - 158 << "\" y=\"" << top + kTop + 2
      << "\" width=\"154\" height=\"" << 16 * static_cast<double>(panel.series.size()) + 6
      << "\" fill=\"white\" fill-opacity=\"0.85\" stroke=\"#ccc\"/>\n";
  for (size_t s = 0; s < panel.series.size(); ++s) {
    const PlotSeries& series = panel.series[s];
    const char* colour = kPalette[s % std::size(kPalette)];
    // One polyline per run of finite values.
    std::string run;
    auto flush = [&] {
      if (!run.empty()) {
        out << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"1.5\" points=\""
            << run << "\"/>\n";
      }
      run.clear();
    };
    std::ostringstream point;
    for (size_t i = 0; i < series.x.size() && i < series.y.size(); ++i) {
      if (!std::isfinite(series.x[i]) || !std::isfinite(series.y[i])) {
        flush();
        continue;
      }
      point.str("");
      point << std::setprecision(5) << px(series.x[i]) << ',' << py(series.y[i]) << ' ';
      run += point.str();
    }
    flush();
    const double legend_y = top + kTop + 14 + 16 * static_cast<double>(s);
    const double legend_x = kLeft + plot_width - 150;
    out << "<line x1=\"" << legend_x << "\" y1=\"" << legend_y - 4 << "\" x2=\"" << legend_x + 20
        << "\" y2=\"" << legend_y - 4 << "\" stroke=\"" << colour
        << "\" stroke-width=\"2\"/>\n<text x=\"" << legend_x + 26 << "\" y=\"" << legend_y
        << "\" font-size=\"12\">" << Escape(series.name) << "</text>\n";
  }
}

}  // namespace

void WriteSvgPanels(std::ostream& out, const std::vector<PlotPanel>& panels) {
  const double height = kPanelHeight * static_cast<double>(panels.size());
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\"" << height
      << "\" viewBox=\"0 0 " << kWidth << ' ' << height
      << "\" font-family=\"sans-serif\" font-size=\"13\">\n<rect width=\"" << kWidth
      << "\" height=\"" << height << "\" fill=\"white\"/>\n";
  for (size_t i = 0; i < panels.size(); ++i) {
    WritePanel(out, panels[i], kPanelHeight * static_cast<double>(i));
  }
  out << "</svg>\n";
}

}  // namespace scallop::cli
