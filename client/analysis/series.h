// The series `scallop analyze` compares: where each one's point sets come
// from (point files, a bounded sampler, windows of a world), and their
// periodogram, radial spectrum and spacing statistics averaged over sets.
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "client/options/world_options.h"
#include "scallop/analysis/periodogram.h"
#include "scallop/analysis/radial_spectrum.h"
#include "scallop/base/status.h"
#include "scallop/geometry/rect.h"
#include "scallop/verify/delaunay_verifier.h"

namespace scallop::cli {

// The command line of `scallop analyze`, as parsed.
struct AnalyzeArguments {
  std::vector<std::string> inputs;
  std::string domain;
  bool torus = false;
  std::vector<std::string> rects;
  std::vector<std::string> algorithms{"a3"};
  std::vector<std::string> labels;
  // --seed, --min-distance, --density and --threads, as every command that
  // names a world takes them; a world series sets `algorithm` from
  // `algorithms`, and `rect` is unused (--rect may be given several times).
  WorldArguments world;
  int sets = 1;
  int max_frequency = 0;  // 0: the default range
  bool dart_exhaustive = false;
  std::string png, plot;
  bool json = false;
  int bands = 4;  // with a radius field (world.field): bands of R the statistics are split by
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

// The series the arguments name, one per file, algorithm or rectangle,
// checked; errors name the option.
StatusOr<std::vector<SeriesPlan>> PlanSeries(const AnalyzeArguments& arguments);

// Every set of `plan` made and measured, the periodograms averaged.
StatusOr<SeriesResult> Analyse(const SeriesPlan& plan, const AnalyzeArguments& arguments);

}  // namespace scallop::cli
