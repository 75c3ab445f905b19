// `scallop analyze`: the periodogram, radial power, anisotropy and spacing
// statistics of point sets (files, a bounded sampler's output or rectangles
// of worlds), averaged over sets, as a PNG, an SVG plot and JSON or text.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

#include "client/analysis/periodogram_image.h"
#include "client/analysis/series.h"
#include "client/analysis/svg_plot.h"
#include "client/commands/analyze_parts.h"
#include "client/commands/command_exit.h"
#include "client/commands/commands.h"
#include "client/options/rect_option.h"

namespace scallop::cli {
namespace {

// Frequencies in cycles per d: r / L * d.
std::vector<double> FrequenciesPerD(const SeriesResult& result, double min_distance) {
  std::vector<double> frequencies;
  for (double r : result.radial.frequency) {
    frequencies.push_back(r / result.plan->window.Width() * min_distance);
  }
  return frequencies;
}

struct Summary {
  double rho_mean, rho_sd, peak_frequency, peak_power, low_power, disk_radius;
};

// Low-frequency power: the mean radial power below half the peak frequency,
// the depth of the low-energy disk (small for good blue noise, 1 for white);
// disk radius: where radial power first reaches 0.5 (NaN if it never does).
Summary Summarise(const SeriesResult& result, double min_distance) {
  const double sets = result.plan->sets;
  Summary summary{};
  summary.rho_mean = result.rho_sum / sets;
  summary.rho_sd = sets > 1 ? std::sqrt(std::max(0.0, (result.rho_squares -
                                                       sets * summary.rho_mean * summary.rho_mean) /
                                                          (sets - 1)))
                            : 0.0;
  const std::vector<double> f = FrequenciesPerD(result, min_distance);
  const size_t peak = PeakAnnulus(result.radial);
  summary.peak_frequency = f[peak];
  summary.peak_power = result.radial.mean_power[peak];
  summary.low_power = LowFrequencyPower(result.radial);
  // The low-energy disk's radius: where radial power first reaches half of
  // white noise's.
  summary.disk_radius = NAN;
  for (size_t i = 0; i < f.size(); ++i) {
    if (result.radial.mean_power[i] >= 0.5) {
      summary.disk_radius = f[i];
      break;
    }
  }
  return summary;
}

nlohmann::json SeriesJson(const SeriesResult& result, double min_distance) {
  const SeriesPlan& plan = *result.plan;
  const Summary summary = Summarise(result, min_distance);
  const double d = min_distance;
  nlohmann::json radial{{"frequency_per_d", FrequenciesPerD(result, d)},
                        {"cycles_per_window", result.radial.frequency},
                        {"power", result.radial.mean_power}};
  nlohmann::json anisotropy = nlohmann::json::array();
  for (double a : result.radial.anisotropy_db) {
    anisotropy.push_back(std::isfinite(a) ? nlohmann::json(a) : nlohmann::json(nullptr));
  }
  radial["anisotropy_db"] = anisotropy;
  return {{"name", plan.name},
          {"source", plan.source},
          {"window", {plan.window.x0, plan.window.y0, plan.window.x1, plan.window.y1}},
          {"window_side_in_d", plan.window.Width() / d},
          {"sets", plan.sets},
          {"mean_points", static_cast<double>(result.points) / plan.sets},
          {"points_outside_window", result.outside},
          {"rho", {{"mean", summary.rho_mean}, {"sd", summary.rho_sd}}},
          {"closest_pair_in_d", result.closest / d},
          {"largest_empty_circle_in_d", result.largest_empty_circle / d},
          {"spacing_violations", result.spacing_violations},
          {"max_frequency", result.max_frequency},
          {"fft_grid", PeriodogramGridSize(result.max_frequency)},
          {"peak", {{"frequency_per_d", summary.peak_frequency}, {"power", summary.peak_power}}},
          {"low_frequency_power", summary.low_power},
          {"low_energy_radius_per_d", summary.disk_radius},
          {"white_noise_anisotropy_db", -10 * std::log10(double(plan.sets))},
          {"radial", radial}};
}

void WriteText(std::ostream& out, const std::vector<SeriesResult>& results, double d) {
  out << std::setprecision(5);
  for (const SeriesResult& result : results) {
    const SeriesPlan& plan = *result.plan;
    const Summary summary = Summarise(result, d);
    out << plan.name << " (" << plan.source << ")\n"
        << "  sets " << plan.sets << ", points per set "
        << static_cast<double>(result.points) / plan.sets << ", window " << plan.window.Width() / d
        << " d square\n"
        << "  rho " << summary.rho_mean << " (sd " << summary.rho_sd << ")\n"
        << "  closest pair " << result.closest / d << " d, largest empty circle "
        << result.largest_empty_circle / d << " d, spacing violations " << result.spacing_violations
        << '\n'
        << "  radial power peak " << summary.peak_power << " at " << summary.peak_frequency
        << " / d; mean below half of it " << summary.low_power << '\n'
        << "  radial power first reaches 0.5 at " << summary.disk_radius << " / d\n";
    if (result.outside > 0)
      out << "  points outside the window, dropped " << result.outside << '\n';
  }
}

Status WritePlot(const std::string& path, const std::vector<SeriesResult>& results, double d) {
  PlotPanel power{.title = "Radial mean power",
                  .x_label = "frequency (cycles per d)",
                  .y_label = "power",
                  .series = {},
                  .references = {{1.0, "white noise"}}};
  PlotPanel anisotropy{.title = "Anisotropy",
                       .x_label = "frequency (cycles per d)",
                       .y_label = "anisotropy (dB)",
                       .series = {},
                       .references = {}};
  for (const SeriesResult& result : results) {
    const std::vector<double> f = FrequenciesPerD(result, d);
    power.series.push_back({result.plan->name, f, result.radial.mean_power});
    anisotropy.series.push_back({result.plan->name, f, result.radial.anisotropy_db});
  }
  const int sets = results.front().plan->sets;
  anisotropy.references.push_back(
      {-10 * std::log10(double(sets)),
       "white noise, " + std::to_string(sets) + (sets == 1 ? " set" : " sets")});
  std::ofstream out(path);
  WriteSvgPanels(out, {power, anisotropy});
  out.close();
  if (!out) return InvalidArgument(path + ": cannot write");
  return Status::Ok();
}

int RunAnalyze(const AnalyzeArguments& arguments);

// --world-file: a layered world is analysed from the file; any other runs as the options that
// name it would (--seed, --min-distance, --algorithm, --density, its field as read from the
// file), so every kind of world takes the same path however it is given.
int RunWorldFileAnalyze(const AnalyzeArguments& arguments) {
  StatusOr<World> world = ParseWorld(arguments.world);
  if (!world.ok()) return ReportBadArguments("analyze", world.status());
  if (world->layers() != nullptr) return RunLayeredAnalyze(arguments);
  const WorldSpec& spec = world->spec();
  AnalyzeArguments named = arguments;
  named.world.world_file.clear();
  named.world.seed = std::to_string(spec.seed);
  named.world.min_distance = spec.min_distance;
  named.world.density = spec.density;
  named.algorithms = {std::string(WorldAlgorithmName(spec.algorithm))};
  if (spec.radius_field.has_value()) return RunFieldAnalyze(named, *spec.radius_field);
  return RunAnalyze(named);
}

int RunAnalyze(const AnalyzeArguments& arguments) {
  if (!arguments.world.world_file.empty()) return RunWorldFileAnalyze(arguments);
  if (HasLayers(arguments.world.layers)) return RunLayeredAnalyze(arguments);
  StatusOr<std::optional<RadiusFieldSpec>> field = ParseLocalField(arguments.world.field);
  if (!field.ok()) return ReportBadArguments("analyze", field.status());
  if (!arguments.plot.empty() &&
      (arguments.plot.size() < 4 || arguments.plot.substr(arguments.plot.size() - 4) != ".svg")) {
    return ReportBadArguments("analyze",
                              InvalidArgument("--plot: writes SVG, give a path ending in .svg"));
  }
  if (field->has_value()) return RunFieldAnalyze(arguments, **field);
  StatusOr<std::vector<SeriesPlan>> plans = PlanSeries(arguments);
  if (!plans.ok()) return ReportBadArguments("analyze", plans.status());
  std::vector<SeriesResult> results;
  for (const SeriesPlan& plan : *plans) {
    StatusOr<SeriesResult> result = Analyse(plan, arguments);
    if (!result.ok()) {
      // Bad values surface here only through the core's checks of the input.
      return ReportBadArguments("analyze",
                                InvalidArgument(plan.name + ": " + result.status().message()));
    }
    results.push_back(std::move(*result));
  }
  const double d = arguments.world.min_distance;
  if (!arguments.png.empty()) {
    std::vector<Periodogram> periodograms;
    for (const SeriesResult& result : results) periodograms.push_back(result.periodogram);
    if (Status status = WritePng(arguments.png, RenderPeriodograms(periodograms)); !status.ok()) {
      std::cerr << "scallop analyze: --png: " << status.message() << '\n';
      return 1;
    }
  }
  if (!arguments.plot.empty()) {
    if (Status status = WritePlot(arguments.plot, results, d); !status.ok()) {
      std::cerr << "scallop analyze: --plot: " << status.message() << '\n';
      return 1;
    }
  }
  if (arguments.json) {
    nlohmann::json series = nlohmann::json::array();
    for (const SeriesResult& result : results) series.push_back(SeriesJson(result, d));
    std::cout << nlohmann::json{{"min_distance", d}, {"series", series}}.dump() << '\n';
  } else {
    WriteText(std::cout, results, d);
  }
  return 0;
}

}  // namespace

CommandRunner RegisterAnalyze(CLI::App& app) {
  auto arguments = std::make_shared<AnalyzeArguments>();
  CLI::App* command = app.add_subcommand(
      "analyze",
      "Periodogram, radial power, anisotropy, rho, closest pair and largest empty circle of "
      "point files, a bounded sampler's output or rectangles of worlds, averaged over sets");
  CLI::Option* input = command->add_option(
      "--input", arguments->inputs,
      "Point file(s) as written by generate/plane/points (CSV or JSON); each is one set");
  CLI::Option* domain = command->add_option(
      "--domain", arguments->domain, "Sampler source: square domain X0,Y0,X1,Y1 (half-open)");
  command->add_flag("--torus", arguments->torus, "Sampler source: wrap the domain's edges");
  command->add_option("--rect", arguments->rects,
                      "World source: square window(s) X0,Y0,X1,Y1, one series each; with "
                      "--input, the window (default: the points' bounding square)");
  command
      ->add_option("--algorithm", arguments->algorithms,
                   "Comma-separated: a1, a2, a3 (worlds and samplers), dart, best-candidate, "
                   "bridson (samplers); one series each. A radius field: a3, or bridson on a "
                   "--domain (Bridson with the field, k = 30). Layers on a --domain: a3 (one "
                   "layer after another) or wei (Wei's multi-class darts, aiming at a3's counts)")
      ->delimiter(',')
      ->capture_default_str();
  command->add_option("--label", arguments->labels, "Series names, one per series, in order")
      ->delimiter(',');
  command->add_option("--seed", arguments->world.seed, "First seed; set s uses seed + s")
      ->capture_default_str();
  command->add_option("--min-distance", arguments->world.min_distance, "Minimum distance d")
      ->capture_default_str();
  command->add_option("--density", arguments->world.density, "r'/2r in (1, 2] for a1 and a2")
      ->capture_default_str();
  command
      ->add_option("--threads", arguments->world.threads,
                   "World source: threads generating regions")
      ->capture_default_str();
  command->add_option("--sets", arguments->sets, "Sets (seeds) averaged per series")
      ->capture_default_str();
  command->add_option("--max-frequency", arguments->max_frequency,
                      "Largest frequency, in cycles per window side (1..256; default 2.5 "
                      "cycles per d, at most 256)");
  command->add_flag("--dart-exhaustive", arguments->dart_exhaustive,
                    "dart: run until no spot is left (maximal)");
  AddFieldOptions(*command, arguments->world.field);
  AddLayerOptions(*command, arguments->world.layers);
  AddWorldFileOption(*command, arguments->world);
  command
      ->add_option("--bands", arguments->bands,
                   "With a radius field: bands of R (geometric) the statistics are split by")
      ->capture_default_str();
  command->add_option("--png", arguments->png,
                      "Write the periodogram(s), side by side, as PNG; with a radius field, the "
                      "first set's points over the field");
  command->add_option("--plot", arguments->plot, "Write radial power and anisotropy as SVG");
  command->add_flag("--json", arguments->json, "Print the numbers as JSON instead of text");
  input->excludes(domain);
  return [arguments] { return RunAnalyze(*arguments); };
}

}  // namespace scallop::cli
