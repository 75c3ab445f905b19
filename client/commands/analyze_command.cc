// `scallop analyze`: the periodogram, radial power, anisotropy and spacing
// statistics of point sets (files, a bounded sampler's output or rectangles
// of worlds), averaged over sets, as a PNG, an SVG plot and JSON or text.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "client/analysis/field_analysis.h"
#include "client/analysis/layer_analysis.h"
#include "client/analysis/layer_sets.h"
#include "client/analysis/periodogram_image.h"
#include "client/analysis/point_file.h"
#include "client/analysis/series.h"
#include "client/analysis/svg_plot.h"
#include "client/commands/command_exit.h"
#include "client/commands/commands.h"
#include "client/options/rect_option.h"
#include "scallop/plane/plane_engine.h"
#include "scallop/sampling/field_sampler.h"

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

nlohmann::json BandJson(const FieldBand& band) {
  const BandSpectrum spectrum = SpectrumOf(band);
  return {
      {"r", {band.r_lo, band.r_hi}},
      {"area", band.area},
      {"points", band.points},
      {"rho", band.Rho()},
      {"nearest_ratio_mean", band.NearestRatio()},
      {"spectrum",
       {{"points", band.pairs.points},
        {"frequency_per_r", spectrum.frequency},
        {"power", spectrum.power},
        {"low_frequency_power", spectrum.low_power},
        {"peak", {{"frequency_per_r", spectrum.peak_frequency}, {"power", spectrum.peak_power}}}}}};
}

// --plot with a radius field: the spectrum normalised by local R, one series a band.
Status WriteFieldPlot(const std::string& path, const FieldStatistics& statistics) {
  PlotPanel power{.title = "Radial power normalised by local R, by band of R",
                  .x_label = "frequency (cycles per R(p))",
                  .y_label = "power",
                  .series = {},
                  .references = {{1.0, "white noise"}}};
  const auto add = [&](const FieldBand& band, const std::string& name) {
    if (band.pairs.points == 0) return;
    const BandSpectrum spectrum = SpectrumOf(band);
    power.series.push_back({name, spectrum.frequency, spectrum.power});
  };
  add(statistics.all, "all");
  for (const FieldBand& band : statistics.bands) {
    std::ostringstream name;
    name << std::setprecision(3) << "R in [" << band.r_lo << ", " << band.r_hi << ")";
    add(band, name.str());
  }
  std::ofstream out(path);
  WriteSvgPanels(out, {power});
  out.close();
  if (!out) return InvalidArgument(path + ": cannot write");
  return Status::Ok();
}

// A radius field's sets (the field sampler on --domain, a world on --rect, or --input files),
// judged against the field: rho and nearest neighbours per band of R, conflicts, pair
// distances over max(R(p), R(q)); --png: the first set over the field.
int RunFieldAnalyze(const AnalyzeArguments& arguments, const RadiusFieldSpec& spec) {
  const auto bad = [](const Status& status) { return ReportBadArguments("analyze", status); };
  StatusOr<RadiusField> field = RadiusField::Create(spec);
  if (!field.ok()) return bad(field.status());
  if (arguments.bands < 1 || arguments.bands > 64) {
    return bad(
        InvalidArgument("--bands: must be in 1..64, got " + std::to_string(arguments.bands)));
  }
  if (arguments.sets < 1 || arguments.sets > 1000) {
    return bad(InvalidArgument("--sets: must be in 1..1000 with a radius field"));
  }
  if (arguments.torus) return bad(InvalidArgument("--torus: a radius field samples rectangles"));
  const std::string algorithm =
      arguments.algorithms.size() == 1 ? arguments.algorithms[0] : "several";
  // The field Bridson baseline is a bounded sampler: analysed on a --domain, for comparison.
  const bool bridson = algorithm == "bridson" && !arguments.domain.empty();
  if (Status status = CheckFieldAlgorithm(arguments.world.field, algorithm);
      !bridson && !status.ok()) {
    return bad(status);
  }
  StatusOr<uint64_t> seed = ParseSeed(arguments.world.seed);
  if (!seed.ok()) return bad(seed.status());
  const int sources = !arguments.inputs.empty() + !arguments.domain.empty() +
                      (!arguments.rects.empty() && arguments.inputs.empty());
  if (sources != 1) {
    return bad(InvalidArgument("--input, --domain or --rect: give one source of points"));
  }
  std::vector<std::vector<Vec2>> sets;
  Rect window;
  if (!arguments.inputs.empty()) {
    for (const std::string& path : arguments.inputs) {
      StatusOr<std::vector<Vec2>> points = ReadPointFile(path);
      if (!points.ok()) return bad(points.status());
      sets.push_back(std::move(*points));
    }
    if (arguments.rects.size() != 1) {
      return bad(InvalidArgument("--rect: give the window the --input points cover"));
    }
  }
  const std::string window_text = !arguments.domain.empty() ? arguments.domain
                                  : arguments.rects.empty() ? ""
                                                            : arguments.rects.front();
  StatusOr<Rect> parsed = ParseRect(window_text, arguments.domain.empty() ? "--rect" : "--domain");
  if (!parsed.ok()) return bad(parsed.status());
  window = *parsed;
  if (!arguments.domain.empty()) {
    for (int s = 0; s < arguments.sets; ++s) {
      const FieldSamplerOptions options{.domain = window, .seed = *seed + static_cast<uint64_t>(s)};
      StatusOr<std::vector<Vec2>> points =
          bridson ? SampleFieldBridson(options, *field) : SampleField(options, *field);
      if (!points.ok()) return bad(points.status());
      sets.push_back(std::move(*points));
    }
  } else if (arguments.inputs.empty()) {
    StatusOr<World> world = World::Create({.seed = *seed, .radius_field = spec});
    if (!world.ok()) return bad(world.status());
    StatusOr<PlaneEngineOptions> engine_options = ParseEngineOptions(arguments.world);
    if (!engine_options.ok()) return bad(engine_options.status());
    PlaneEngine engine(*engine_options);
    for (int s = 0; s < arguments.sets; ++s) {
      StatusOr<PlanePoints> points =
          engine.Points(world->WithSeed(*seed + static_cast<uint64_t>(s)), window);
      if (!points.ok()) return bad(points.status());
      sets.push_back(std::move(points->positions));
    }
  }
  FieldStatistics statistics;
  for (const std::vector<Vec2>& points : sets) {
    AddFieldStatistics(points, *field, window, arguments.bands, statistics);
  }
  if (!arguments.png.empty()) {
    if (Status status =
            WritePng(arguments.png, RenderPointsOverField(sets.front(), *field, window, 800));
        !status.ok()) {
      std::cerr << "scallop analyze: --png: " << status.message() << '\n';
      return 1;
    }
  }
  if (!arguments.plot.empty()) {
    if (Status status = WriteFieldPlot(arguments.plot, statistics); !status.ok()) {
      std::cerr << "scallop analyze: --plot: " << status.message() << '\n';
      return 1;
    }
  }
  if (arguments.json) {
    nlohmann::json bands = nlohmann::json::array();
    for (const FieldBand& band : statistics.bands) bands.push_back(BandJson(band));
    std::vector<double> ratios;
    for (size_t b = 0; b < statistics.pair_ratio_counts.size(); ++b) {
      ratios.push_back((b + 0.5) * kPairRatioStep);
    }
    std::cout << nlohmann::json{{"field", RadiusFieldKindName(field->kind())},
                                {"r_min", field->r_min()},
                                {"r_max", field->r_max()},
                                {"window", {window.x0, window.y0, window.x1, window.y1}},
                                {"sets", sets.size()},
                                {"all", BandJson(statistics.all)},
                                {"bands", bands},
                                {"conflicts", statistics.conflicts},
                                {"smallest_pair_ratio", statistics.smallest_ratio},
                                {"pair_ratio",
                                 {{"ratio", ratios},
                                  {"neighbours_per_point", statistics.PairRatioPerPoint()}}}}
                     .dump()
              << '\n';
    return 0;
  }
  std::cout << std::setprecision(5) << RadiusFieldKindName(field->kind()) << " field, R in ["
            << field->r_min() << ", " << field->r_max() << "], " << sets.size() << " sets\n"
            << "  all: " << statistics.all.points << " points, rho " << statistics.all.Rho()
            << " (normalised by local R), nearest neighbour " << statistics.all.NearestRatio()
            << " max(R)\n"
            << "  conflicts " << statistics.conflicts << ", smallest pair "
            << statistics.smallest_ratio << " max(R)\n";
  const auto print_spectrum = [](const FieldBand& band) {
    if (band.pairs.points == 0) return;
    const BandSpectrum spectrum = SpectrumOf(band);
    std::cout << "    spectrum per local R (" << band.pairs.points << " points): mean power below "
              << "0.5 / R " << spectrum.low_power << ", peak " << spectrum.peak_power << " at "
              << spectrum.peak_frequency << " / R\n";
  };
  print_spectrum(statistics.all);
  for (const FieldBand& band : statistics.bands) {
    std::cout << "  R in [" << band.r_lo << ", " << band.r_hi << "): " << band.points
              << " points, area " << band.area << ", rho " << band.Rho() << ", nearest "
              << band.NearestRatio() << " max(R)\n";
    print_spectrum(band);
  }
  return 0;
}

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
  const auto peak_of = [&](const LayerSpectrum& layer) {
    size_t peak = 0;
    for (size_t i = 0; i < layer.radial.mean_power.size(); ++i) {
      if (layer.radial.mean_power[i] > layer.radial.mean_power[peak]) peak = i;
    }
    return peak;
  };
  const auto per_d = [&](const LayerSpectrum& layer, double cycles) {
    return cycles / window->Width() * layer.spacing;
  };
  // As Summarise's: the mean radial power below half the peak's frequency.
  const auto low_power_of = [&](const LayerSpectrum& layer) {
    const double half_peak = layer.radial.frequency[peak_of(layer)] / 2;
    double sum = 0;
    int count = 0;
    for (size_t i = 0; i < layer.radial.frequency.size() && layer.radial.frequency[i] < half_peak;
         ++i, ++count) {
      sum += layer.radial.mean_power[i];
    }
    return count > 0 ? sum / count : NAN;
  };
  nlohmann::json layers = nlohmann::json::array();
  for (const LayerSpectrum& layer : analysis->layers) {
    std::vector<double> frequencies;
    for (double f : layer.radial.frequency) frequencies.push_back(per_d(layer, f));
    const size_t peak = peak_of(layer);
    layers.push_back(
        {{"name", layer.name},
         {"spacing", layer.spacing},
         {"mean_points", static_cast<double>(layer.points) / arguments.sets},
         {"rho", layer.rho},
         {"peak",
          {{"frequency_per_d", frequencies[peak]}, {"power", layer.radial.mean_power[peak]}}},
         {"low_frequency_power", low_power_of(layer)},
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
    const size_t peak = peak_of(layer);
    std::cout << layer.name << " (d " << layer.spacing
              << "): " << static_cast<double>(layer.points) / arguments.sets
              << " points a set, rho " << layer.rho << ", radial power peak "
              << layer.radial.mean_power[peak] << " at "
              << per_d(layer, layer.radial.frequency[peak]) << " / d, low-frequency power "
              << low_power_of(layer) << "\n";
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
