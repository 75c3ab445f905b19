// `scallop analyze` with layers: each layer's and the union's spectrum and rho, and the pair
// distances across layers (docs/quality.md, "Layered worlds").
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

#include "client/analysis/layer_analysis.h"
#include "client/analysis/layer_sets.h"
#include "client/analysis/periodogram_image.h"
#include "client/commands/analyze_parts.h"
#include "client/commands/command_exit.h"
#include "client/options/rect_option.h"
#include "client/options/world_options.h"
#include "scallop/plane/plane_engine.h"

namespace scallop::cli {

// A layered world's sets, on one --rect window of the plane or sampled on a --domain alone (a3:
// one layer after another; wei: Wei's joint scheme, for comparison): each layer's spectrum and
// rho, the union's, and the pair distances across layers over D; --png: the layers' and the
// union's periodograms.
int RunLayeredAnalyze(const AnalyzeArguments& arguments) {
  const auto bad = [](const Status& status) { return ReportBadArguments("analyze", status); };
  const bool bounded = !arguments.domain.empty();
  if (!arguments.inputs.empty() || arguments.rects.size() != (bounded ? 0 : 1)) {
    return bad(InvalidArgument(
        "--rect: a layered world is analysed on one --rect window or sampled on a --domain"));
  }
  if (arguments.algorithms.size() != 1) {
    return bad(InvalidArgument("--algorithm: one algorithm with layers"));
  }
  if (!arguments.plot.empty()) return bad(InvalidArgument("--plot: not with layers"));
  if (arguments.sets < 1 || arguments.sets > 1000) {
    return bad(InvalidArgument("--sets: must be in 1..1000 with layers"));
  }
  StatusOr<World> world = ParseWorld(arguments.world);
  if (!world.ok()) return bad(world.status());
  StatusOr<Rect> window = bounded ? ParseRect(arguments.domain, "--domain")
                                  : ParseRect(arguments.rects.front(), "--rect");
  if (!window.ok()) return bad(window.status());
  const auto make_sets = [&]() -> StatusOr<std::vector<PlanePoints>> {
    if (bounded) {
      return BoundedLayerSets(*world, *window, arguments.algorithms.front(), arguments.sets);
    }
    if (arguments.algorithms.front() != "a3") {
      return InvalidArgument("--algorithm: a layered world is a3's; wei needs --domain");
    }
    StatusOr<PlaneEngineOptions> engine_options = ParseEngineOptions(arguments.world);
    if (!engine_options.ok()) return engine_options.status();
    PlaneEngine engine(*engine_options);
    return WorldLayerSets(*world, *window, arguments.sets, engine);
  };
  StatusOr<std::vector<PlanePoints>> sets = make_sets();
  if (!sets.ok()) return bad(sets.status());
  // As for worlds: 2.5 cycles per (smallest) d by default, at most 256 per window.
  const int max_frequency =
      arguments.max_frequency > 0
          ? arguments.max_frequency
          : std::clamp(static_cast<int>(std::ceil(2.5 * window->Width() / world->min_distance())),
                       1, kMaxPeriodogramFrequency);
  StatusOr<LayeredAnalysis> analysis = AnalyseLayers(*sets, *world, *window, max_frequency);
  if (!analysis.ok()) return bad(analysis.status());
  if (!arguments.png.empty()) {
    std::vector<Periodogram> periodograms;
    for (const LayerSpectrum& layer : analysis->layers) periodograms.push_back(layer.periodogram);
    if (Status status = WritePng(arguments.png, RenderPeriodograms(periodograms)); !status.ok()) {
      std::cerr << "scallop analyze: --png: " << status.message() << '\n';
      return 1;
    }
  }
  const auto per_d = [&](const LayerSpectrum& layer, double cycles) {
    return cycles / window->Width() * layer.spacing;
  };
  nlohmann::json layers = nlohmann::json::array();
  for (const LayerSpectrum& layer : analysis->layers) {
    std::vector<double> frequencies;
    for (double f : layer.radial.frequency) frequencies.push_back(per_d(layer, f));
    const size_t peak = PeakAnnulus(layer.radial);
    layers.push_back(
        {{"name", layer.name},
         {"spacing", layer.spacing},
         {"mean_points", static_cast<double>(layer.points) / arguments.sets},
         {"rho", layer.rho},
         {"peak",
          {{"frequency_per_d", frequencies[peak]}, {"power", layer.radial.mean_power[peak]}}},
         {"low_frequency_power", LowFrequencyPower(layer.radial)},
         {"radial", {{"frequency_per_d", frequencies}, {"power", layer.radial.mean_power}}}});
  }
  nlohmann::json cross = nlohmann::json::array();
  for (const CrossHistogram& histogram : analysis->cross) {
    std::vector<double> ratios;
    for (size_t b = 0; b < histogram.per_point.size(); ++b)
      ratios.push_back((b + 0.5) * kCrossRatioStep);
    cross.push_back({{"from", analysis->layers[static_cast<size_t>(histogram.a)].name},
                     {"to", analysis->layers[static_cast<size_t>(histogram.b)].name},
                     {"distance", histogram.distance},
                     {"centres", histogram.centres},
                     {"ratio", ratios},
                     {"neighbours_per_point", histogram.per_point}});
  }
  if (arguments.json) {
    std::cout << nlohmann::json{{"window", {window->x0, window->y0, window->x1, window->y1}},
                                {"sets", arguments.sets},
                                {"max_frequency", max_frequency},
                                {"layers", layers},
                                {"cross", cross}}
                     .dump()
              << '\n';
    return 0;
  }
  std::cout << std::setprecision(5);
  for (const LayerSpectrum& layer : analysis->layers) {
    const size_t peak = PeakAnnulus(layer.radial);
    std::cout << layer.name << " (d " << layer.spacing
              << "): " << static_cast<double>(layer.points) / arguments.sets
              << " points a set, rho " << layer.rho << ", radial power peak "
              << layer.radial.mean_power[peak] << " at "
              << per_d(layer, layer.radial.frequency[peak]) << " / d, low-frequency power "
              << LowFrequencyPower(layer.radial) << "\n";
  }
  for (const CrossHistogram& histogram : analysis->cross) {
    // The first ratio bin holding a neighbour: >= 1 when the layers keep D.
    double nearest = NAN;
    double within = 0;  // neighbours per point closer than 1.5 D
    for (size_t b = 0; b < histogram.per_point.size(); ++b) {
      if (histogram.per_point[b] > 0 && std::isnan(nearest)) nearest = b * kCrossRatioStep;
      if ((b + 1) * kCrossRatioStep <= 1.5) within += histogram.per_point[b];
    }
    std::cout << analysis->layers[static_cast<size_t>(histogram.b)].name << " around "
              << analysis->layers[static_cast<size_t>(histogram.a)].name << " (D "
              << histogram.distance << "): nearest from " << nearest << " D, " << within
              << " within 1.5 D a point\n";
  }
  return 0;
}

}  // namespace scallop::cli
