// The series `scallop analyze` compares, planned from its options (see
// series.h); a world's sets come from the core's VerifyWorldRect, which reads
// the window with the verifier's halo and returns the window's points.
#include "client/analysis/series.h"

#include <cmath>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>

#include "client/analysis/point_file.h"
#include "client/options/rect_option.h"
#include "client/options/world_options.h"
#include "scallop/analysis/periodogram.h"
#include "scallop/analysis/point_statistics.h"
#include "scallop/analysis/radial_spectrum.h"
#include "scallop/plane/plane_engine.h"
#include "scallop/plane/query_rect.h"
#include "scallop/plane/world_verifier.h"
#include "scallop/sampling/sampler.h"
#include "scallop/verify/delaunay_verifier.h"

namespace scallop::cli {
namespace {

// Bounds that keep a typo from running for days; the docs' figures use 100.
constexpr int kMaxSets = 100000;
// What one set of a world series may read: its window and the verifier's halo.
constexpr QueryLimit kWorldAnalysisLimit{.max_area = 1e8, .name = "scallop analyze's limit"};
// Default frequency range: 2.5 cycles per d shows the low-energy annulus, the
// peak near 1 / d and the flat tail beyond it.
constexpr double kDefaultCyclesPerD = 2.5;

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
    plan.window = BoundingSquare(*files, arguments.world.min_distance);
  } else {
    StatusOr<Rect> window = ParseRect(arguments.rects.front(), "--rect");
    if (!window.ok()) return window.status();
    if (Status status = RequireSquare(*window, "--rect"); !status.ok()) return status;
    plan.window = *window;
  }
  plan.sets = static_cast<int>(files->size());
  const Rect window = plan.window;
  const double d = arguments.world.min_distance;
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
  StatusOr<uint64_t> seed = ParseSeed(arguments.world.seed);
  if (!seed.ok()) return seed.status();
  std::vector<SeriesPlan> plans;
  for (const std::string& name : arguments.algorithms) {
    StatusOr<Algorithm> algorithm = ParseAlgorithm(name);
    if (!algorithm.ok()) return InvalidArgument("--algorithm: " + algorithm.status().message());
    SamplerOptions options;
    options.algorithm = *algorithm;
    options.domain = {*domain, arguments.torus};
    options.min_distance = arguments.world.min_distance;
    options.density = arguments.world.density;
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
  StatusOr<PlaneEngineOptions> engine_options = ParseEngineOptions(arguments.world);
  if (!engine_options.ok()) return engine_options.status();
  auto engine = std::make_shared<PlaneEngine>(*engine_options);
  std::vector<SeriesPlan> plans;
  for (const std::string& algorithm : arguments.algorithms) {
    WorldArguments world_arguments = arguments.world;
    world_arguments.algorithm = algorithm;
    StatusOr<World> world = ParseWorld(world_arguments);
    if (!world.ok()) return world.status();
    for (const std::string& text : arguments.rects) {
      StatusOr<Rect> window = ParseRect(text, "--rect");
      if (!window.ok()) return window.status();
      if (Status status = RequireSquare(*window, "--rect"); !status.ok()) return status;
      // What the first set reads (the window and the verifier's halo) is
      // checked now, so a bad --rect fails before any work.
      if (Status status = CheckQueryRect(*world, Grown(*window, 2 * world->min_distance()),
                                         kWorldAnalysisLimit, "--rect+halo");
          !status.ok()) {
        return status;
      }
      SeriesPlan plan;
      plan.source = "world";
      plan.name = algorithm + (arguments.rects.size() > 1 ? " " + text : "");
      plan.window = *window;
      plan.sets = arguments.sets;
      plan.make = [engine, world = *world, window = *window](int set) -> StatusOr<AnalysedSet> {
        // Set s is the world of seed + s (modulo 2^64), alike in all else.
        PlanePoints inside;
        StatusOr<VerifyReport> report =
            VerifyWorldRect(*engine, world.WithSeed(world.seed() + static_cast<uint64_t>(set)),
                            window, kWorldAnalysisLimit, &inside);
        if (!report.ok()) return report.status();
        if (inside.positions.empty()) return InvalidArgument("--rect: too small to hold a point");
        return AnalysedSet{std::move(inside.positions), 0, *report};
      };
      plans.push_back(std::move(plan));
    }
  }
  return plans;
}

}  // namespace

StatusOr<std::vector<SeriesPlan>> PlanSeries(const AnalyzeArguments& arguments) {
  if (arguments.sets < 1 || arguments.sets > kMaxSets) {
    return InvalidArgument("--sets: must be in 1.." + std::to_string(kMaxSets) + ", got " +
                           std::to_string(arguments.sets));
  }
  if (!std::isfinite(arguments.world.min_distance) || !(arguments.world.min_distance > 0)) {
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
                             : static_cast<int>(std::clamp(std::ceil(kDefaultCyclesPerD * side /
                                                                     arguments.world.min_distance),
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
    StatusOr<double> rho =
        NormalisedRadius(count, plan.window.Area(), arguments.world.min_distance);
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

}  // namespace scallop::cli
