// `scallop analyze`: the periodogram, radial power, anisotropy and spacing
// statistics of point sets (files, a bounded sampler's output or rectangles
// of worlds), averaged over sets, as a PNG, an SVG plot and JSON or text.
#include <charconv>
#include <cmath>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>

#include "analysis_periodogram_image.h"
#include "analysis_point_file.h"
#include "analysis_svg_plot.h"
#include "commands.h"
#include "rect_option.h"
#include "scallop/analysis/periodogram.h"
#include "scallop/analysis/point_statistics.h"
#include "scallop/analysis/radial_spectrum.h"
#include "scallop/plane/plane_engine.h"
#include "scallop/sampling/sampler.h"
#include "scallop/verify/delaunay_verifier.h"
#include "world_options.h"

namespace scallop::cli {
namespace {

// Bounds that keep a typo from running for days; the docs' figures use 100.
constexpr int kMaxSets = 100000;
constexpr int kMaxThreads = 256;
// Default frequency range: 2.5 cycles per d shows the low-energy annulus, the
// peak near 1 / d and the flat tail beyond it.
constexpr double kDefaultCyclesPerD = 2.5;

struct AnalyzeArguments {
  std::vector<std::string> inputs;
  std::string domain;
  bool torus = false;
  std::vector<std::string> rects;
  std::vector<std::string> algorithms{"a3"};
  std::vector<std::string> labels;
  std::string seed = "1";
  double min_distance = 1.0;
  double density = 2.0;
  int threads = 2;
  int sets = 1;
  int max_frequency = 0;  // 0: the default range
  bool dart_exhaustive = false;
  std::string png, plot;
  bool json = false;
};

// One set to analyse: the points inside the window and the verifier's report.
struct AnalysedSet {
  std::vector<Vec2> inside;
  int64_t outside = 0;  // file points outside --rect, dropped
  VerifyReport report;
};

// What one series averages: a window and the function making its set s.
struct SeriesPlan {
  std::string name;
  std::string source;  // "file", "sampler" or "world"
  Rect window;
  int sets = 1;
  std::function<StatusOr<AnalysedSet>(int set)> make;
};

struct SeriesResult {
  const SeriesPlan* plan = nullptr;
  int max_frequency = 0;
  Periodogram periodogram;
  RadialSpectrum radial;
  int64_t points = 0, outside = 0, spacing_violations = 0;
  double rho_sum = 0, rho_squares = 0;
  double closest = std::numeric_limits<double>::infinity();
  double largest_empty_circle = 0;
};

StatusOr<uint64_t> ParseSeed(const std::string& text) {
  uint64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size()) {
    return InvalidArgument("--seed: must be an integer in 0..2^64-1, got '" + text + "'");
  }
  return value;
}

Status RequireSquare(const Rect& window, const std::string& option) {
  const double width = window.Width(), height = window.Height();
  if (std::abs(width - height) > 1e-9 * std::max(width, height)) {
    std::ostringstream message;
    message << option << ": the periodogram needs a square window, got " << width << " x "
            << height;
    return InvalidArgument(message.str());
  }
  return Status::Ok();
}

// The smallest square with its corner at the lowest x and y that holds every
// point of every set in its half-open extent.
Rect BoundingSquare(const std::vector<std::vector<Vec2>>& sets, double min_distance) {
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (const auto& points : sets) {
    for (const Vec2& p : points) {
      x0 = std::min(x0, p.x), y0 = std::min(y0, p.y);
      x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
    }
  }
  double side = std::max(x1 - x0, y1 - y0);
  if (!(side > 0)) side = min_distance;
  // Grow by a hair so the largest coordinate is strictly inside.
  side += std::max(side * 1e-12, 4 * std::numeric_limits<double>::min());
  Rect window{x0, y0, x0 + side, y0 + side};
  window.x1 = std::max(window.x1, std::nextafter(x1, INFINITY));
  window.y1 = std::max(window.y1, std::nextafter(y1, INFINITY));
  return window;
}

StatusOr<std::vector<SeriesPlan>> PlanFiles(const AnalyzeArguments& arguments) {
  if (!arguments.domain.empty()) return InvalidArgument("--input: cannot be used with --domain");
  if (arguments.torus) return InvalidArgument("--torus: only with --domain");
  if (arguments.rects.size() > 1) return InvalidArgument("--rect: at most one with --input");
  if (arguments.sets != 1) {
    return InvalidArgument("--sets: with --input, each file is a set; give several --input");
  }
  auto files = std::make_shared<std::vector<std::vector<Vec2>>>();
  for (const std::string& path : arguments.inputs) {
    StatusOr<std::vector<Vec2>> points = ReadPointFile(path);
    if (!points.ok()) return points.status();
    files->push_back(std::move(*points));
  }
  SeriesPlan plan;
  plan.source = "file";
  plan.name = arguments.inputs.front();
  if (arguments.inputs.size() > 1) {
    plan.name += " and " + std::to_string(arguments.inputs.size() - 1) + " more";
  }
  if (arguments.rects.empty()) {
    plan.window = BoundingSquare(*files, arguments.min_distance);
  } else {
    StatusOr<Rect> window = ParseRect(arguments.rects.front(), "--rect");
    if (!window.ok()) return window.status();
    if (Status status = RequireSquare(*window, "--rect"); !status.ok()) return status;
    plan.window = *window;
  }
  plan.sets = static_cast<int>(files->size());
  const Rect window = plan.window;
  const double d = arguments.min_distance;
  plan.make = [files, window, d](int set) -> StatusOr<AnalysedSet> {
    AnalysedSet result;
    for (const Vec2& p : (*files)[set]) {
      if (window.Contains(p)) {
        result.inside.push_back(p);
      } else {
        ++result.outside;
      }
    }
    if (result.inside.empty()) return InvalidArgument("--rect: holds no point of a file");
    StatusOr<VerifyReport> report = VerifyDomain(result.inside, Domain{window, false}, d);
    if (!report.ok()) return report.status();
    result.report = *report;
    return result;
  };
  return std::vector<SeriesPlan>{std::move(plan)};
}

StatusOr<std::vector<SeriesPlan>> PlanSamplers(const AnalyzeArguments& arguments) {
  StatusOr<Rect> domain = ParseRect(arguments.domain, "--domain");
  if (!domain.ok()) return domain.status();
  if (Status status = RequireSquare(*domain, "--domain"); !status.ok()) return status;
  StatusOr<uint64_t> seed = ParseSeed(arguments.seed);
  if (!seed.ok()) return seed.status();
  std::vector<SeriesPlan> plans;
  for (const std::string& name : arguments.algorithms) {
    StatusOr<Algorithm> algorithm = ParseAlgorithm(name);
    if (!algorithm.ok()) return InvalidArgument("--algorithm: " + algorithm.status().message());
    SamplerOptions options;
    options.algorithm = *algorithm;
    options.domain = {*domain, arguments.torus};
    options.min_distance = arguments.min_distance;
    options.density = arguments.density;
    options.dart_exhaustive = arguments.dart_exhaustive;
    if (Status status = ValidateSamplerOptions(options); !status.ok()) return status;
    SeriesPlan plan;
    plan.source = "sampler";
    plan.name = std::string(AlgorithmName(*algorithm));
    plan.window = *domain;
    plan.sets = arguments.sets;
    const uint64_t first_seed = *seed;
    plan.make = [options, first_seed](int set) mutable -> StatusOr<AnalysedSet> {
      options.seed = first_seed + static_cast<uint64_t>(set);  // wraps modulo 2^64
      StatusOr<std::vector<Vec2>> points = Sample(options);
      if (!points.ok()) return points.status();
      AnalysedSet result;
      result.inside = std::move(*points);
      StatusOr<VerifyReport> report =
          VerifyDomain(result.inside, options.domain, options.min_distance);
      if (!report.ok()) return report.status();
      result.report = *report;
      return result;
    };
    plans.push_back(std::move(plan));
  }
  return plans;
}

StatusOr<std::vector<SeriesPlan>> PlanWorlds(const AnalyzeArguments& arguments) {
  if (arguments.torus) return InvalidArgument("--torus: only with --domain");
  if (arguments.threads < 1 || arguments.threads > kMaxThreads) {
    return InvalidArgument("--threads: must be in 1.." + std::to_string(kMaxThreads));
  }
  auto engine = std::make_shared<PlaneEngine>(PlaneEngineOptions{.threads = arguments.threads});
  std::vector<SeriesPlan> plans;
  for (const std::string& algorithm : arguments.algorithms) {
    WorldArguments world_arguments;
    world_arguments.seed = arguments.seed;
    world_arguments.min_distance = arguments.min_distance;
    world_arguments.algorithm = algorithm;
    world_arguments.density = arguments.density;
    StatusOr<World> world = ParseWorld(world_arguments);
    if (!world.ok()) return world.status();
    for (const std::string& text : arguments.rects) {
      StatusOr<Rect> window = ParseRect(text, "--rect");
      if (!window.ok()) return window.status();
      if (Status status = RequireSquare(*window, "--rect"); !status.ok()) return status;
      // The verifier needs every point within 2 d of the window.
      const double halo = 2 * world->min_distance;
      const Rect query{window->x0 - halo, window->y0 - halo, window->x1 + halo, window->y1 + halo};
      if (Status status = engine->ValidateQuery(*world, query); !status.ok()) {
        return InvalidArgument("--rect (grown by 2 d): " + status.message());
      }
      SeriesPlan plan;
      plan.source = "world";
      plan.name = algorithm + (arguments.rects.size() > 1 ? " " + text : "");
      plan.window = *window;
      plan.sets = arguments.sets;
      plan.make = [engine, world = *world, query,
                   window = *window](int set) mutable -> StatusOr<AnalysedSet> {
        World this_world = world;
        this_world.seed = world.seed + static_cast<uint64_t>(set);  // wraps modulo 2^64
        StatusOr<PlanePoints> points = engine->Points(this_world, query);
        if (!points.ok()) return points.status();
        AnalysedSet result;
        for (const Vec2& p : points->positions) {
          if (window.Contains(p)) result.inside.push_back(p);
        }
        if (result.inside.empty()) return InvalidArgument("--rect: too small to hold a point");
        StatusOr<VerifyReport> report =
            VerifyWindow(points->positions, window, this_world.min_distance);
        if (!report.ok()) return report.status();
        result.report = *report;
        return result;
      };
      plans.push_back(std::move(plan));
    }
  }
  return plans;
}

StatusOr<std::vector<SeriesPlan>> PlanSeries(const AnalyzeArguments& arguments) {
  if (arguments.sets < 1 || arguments.sets > kMaxSets) {
    return InvalidArgument("--sets: must be in 1.." + std::to_string(kMaxSets) + ", got " +
                           std::to_string(arguments.sets));
  }
  if (!std::isfinite(arguments.min_distance) || !(arguments.min_distance > 0)) {
    return InvalidArgument("--min-distance: must be finite and > 0");
  }
  if (arguments.max_frequency != 0 &&
      (arguments.max_frequency < 1 || arguments.max_frequency > kMaxPeriodogramFrequency)) {
    return InvalidArgument("--max-frequency: must be in 1.." +
                           std::to_string(kMaxPeriodogramFrequency) + ", got " +
                           std::to_string(arguments.max_frequency));
  }
  StatusOr<std::vector<SeriesPlan>> plans =
      !arguments.inputs.empty()   ? PlanFiles(arguments)
      : !arguments.domain.empty() ? PlanSamplers(arguments)
      : !arguments.rects.empty()
          ? PlanWorlds(arguments)
          : StatusOr<std::vector<SeriesPlan>>(InvalidArgument(
                "scallop analyze: give --input FILE, --domain X0,Y0,X1,Y1 or --rect X0,Y0,X1,Y1"));
  if (!plans.ok()) return plans;
  if (!arguments.labels.empty()) {
    if (arguments.labels.size() != plans->size()) {
      return InvalidArgument("--label: " + std::to_string(plans->size()) +
                             " series need as many labels, got " +
                             std::to_string(arguments.labels.size()));
    }
    for (size_t i = 0; i < plans->size(); ++i) (*plans)[i].name = arguments.labels[i];
  }
  return plans;
}

StatusOr<SeriesResult> Analyse(const SeriesPlan& plan, const AnalyzeArguments& arguments) {
  SeriesResult result;
  result.plan = &plan;
  const double side = plan.window.Width();
  result.max_frequency = arguments.max_frequency != 0
                             ? arguments.max_frequency
                             : static_cast<int>(std::clamp(
                                   std::ceil(kDefaultCyclesPerD * side / arguments.min_distance),
                                   1.0, double{kMaxPeriodogramFrequency}));
  PeriodogramAverage average;
  for (int set = 0; set < plan.sets; ++set) {
    StatusOr<AnalysedSet> points = plan.make(set);
    if (!points.ok()) return points.status();
    StatusOr<Periodogram> periodogram =
        ComputePeriodogram(points->inside, plan.window, result.max_frequency);
    if (!periodogram.ok()) return periodogram.status();
    if (Status status = average.Add(*periodogram); !status.ok()) return status;
    const auto count = static_cast<int64_t>(points->inside.size());
    StatusOr<double> rho = NormalisedRadius(count, plan.window.Area(), arguments.min_distance);
    if (!rho.ok()) return rho.status();
    result.points += count;
    result.outside += points->outside;
    result.rho_sum += *rho;
    result.rho_squares += *rho * *rho;
    result.closest = std::min(result.closest, points->report.min_distance);
    result.largest_empty_circle =
        std::max(result.largest_empty_circle, points->report.largest_empty_circle);
    result.spacing_violations += points->report.spacing_violations;
  }
  StatusOr<Periodogram> mean = average.Mean();
  if (!mean.ok()) return mean.status();
  result.periodogram = *mean;
  StatusOr<RadialSpectrum> radial = ComputeRadialSpectrum(result.periodogram);
  if (!radial.ok()) return radial.status();
  result.radial = *radial;
  return result;
}

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
  size_t peak = 0;
  for (size_t i = 0; i < f.size(); ++i) {
    if (result.radial.mean_power[i] > result.radial.mean_power[peak]) peak = i;
  }
  summary.peak_frequency = f[peak];
  summary.peak_power = result.radial.mean_power[peak];
  double low = 0;
  int count = 0;
  for (size_t i = 0; i < f.size() && f[i] < f[peak] / 2; ++i, ++count) {
    low += result.radial.mean_power[i];
  }
  summary.low_power = count > 0 ? low / count : NAN;
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

int RunAnalyze(const AnalyzeArguments& arguments) {
  StatusOr<std::vector<SeriesPlan>> plans = PlanSeries(arguments);
  if (!plans.ok()) {
    std::cerr << "scallop analyze: " << plans.status().message() << '\n';
    return 2;
  }
  if (!arguments.plot.empty() &&
      (arguments.plot.size() < 4 || arguments.plot.substr(arguments.plot.size() - 4) != ".svg")) {
    std::cerr << "scallop analyze: --plot: writes SVG, give a path ending in .svg\n";
    return 2;
  }
  std::vector<SeriesResult> results;
  for (const SeriesPlan& plan : *plans) {
    StatusOr<SeriesResult> result = Analyse(plan, arguments);
    if (!result.ok()) {
      // Bad values surface here only through the core's checks of the input.
      std::cerr << "scallop analyze: " << plan.name << ": " << result.status().message() << '\n';
      return 2;
    }
    results.push_back(std::move(*result));
  }
  const double d = arguments.min_distance;
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
                   "bridson (samplers); one series each")
      ->delimiter(',')
      ->capture_default_str();
  command->add_option("--label", arguments->labels, "Series names, one per series, in order")
      ->delimiter(',');
  command->add_option("--seed", arguments->seed, "First seed; set s uses seed + s")
      ->capture_default_str();
  command->add_option("--min-distance", arguments->min_distance, "Minimum distance d")
      ->capture_default_str();
  command->add_option("--density", arguments->density, "r'/2r in (1, 2] for a1 and a2")
      ->capture_default_str();
  command->add_option("--threads", arguments->threads, "World source: threads generating regions")
      ->capture_default_str();
  command->add_option("--sets", arguments->sets, "Sets (seeds) averaged per series")
      ->capture_default_str();
  command->add_option("--max-frequency", arguments->max_frequency,
                      "Largest frequency, in cycles per window side (1..256; default 2.5 "
                      "cycles per d, at most 256)");
  command->add_flag("--dart-exhaustive", arguments->dart_exhaustive,
                    "dart: run until no spot is left (maximal)");
  command->add_option("--png", arguments->png, "Write the periodogram(s), side by side, as PNG");
  command->add_option("--plot", arguments->plot, "Write radial power and anisotropy as SVG");
  command->add_flag("--json", arguments->json, "Print the numbers as JSON instead of text");
  input->excludes(domain);
  return [arguments] { return RunAnalyze(*arguments); };
}

}  // namespace scallop::cli
