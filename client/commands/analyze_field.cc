// `scallop analyze` with a radius field: rho, nearest neighbours and the spectrum normalised by
// local R, per band of R (docs/quality.md, "Radius fields").
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "client/analysis/field_analysis.h"
#include "client/analysis/point_file.h"
#include "client/analysis/svg_plot.h"
#include "client/commands/analyze_parts.h"
#include "client/commands/command_exit.h"
#include "client/options/field_options.h"
#include "client/options/rect_option.h"
#include "client/options/world_options.h"
#include "scallop/plane/plane_engine.h"
#include "scallop/sampling/field_sampler.h"

namespace scallop::cli {
namespace {

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

}  // namespace

// A radius field's sets (the field sampler or the field Bridson on --domain, a world on --rect,
// or --input files), judged against the field: rho and nearest neighbours per band of R,
// conflicts, pair distances over max(R(p), R(q)); --png: the first set over the field.
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

}  // namespace scallop::cli
