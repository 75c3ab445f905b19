// `scallop generate`: runs one bounded-domain sampler locally and prints its
// points, with optional statistics on stderr. With a radius field (--radius-noise,
// --radius-raster) the sampler is the field sampler (SampleField), and each point carries R.
// With layers (--layer, --exclusion) every layer is sampled on the domain (SampleLayers), and
// each point carries its layer.
#include <chrono>
#include <iomanip>
#include <iostream>
#include <memory>

#include "client/commands/command_exit.h"
#include "client/commands/commands.h"
#include "client/options/field_options.h"
#include "client/options/format_options.h"
#include "client/options/layer_options.h"
#include "client/options/rect_option.h"
#include "client/options/world_options.h"
#include "client/output/point_output.h"
#include "scallop/analysis/point_statistics.h"
#include "scallop/plane/world_layers.h"
#include "scallop/sampling/field_sampler.h"
#include "scallop/sampling/layered_sampler.h"
#include "scallop/sampling/sampler.h"

namespace scallop::cli {
namespace {

struct GenerateArguments {
  std::string algorithm = "a3";
  double min_distance = 1.0;
  std::string domain = "0,0,100,100";
  bool torus = false;
  double density = 2.0;
  std::string seed = "1";  // text: CLI11 would wrap "-1" and saturate 2^64 silently
  PointFormat format = PointFormat::kCsv;
  bool stats = false;
  int64_t dart_failure_limit = 100000;
  bool dart_exhaustive = false;
  FieldArguments field;
  LayerArguments layers;
};

// The field sampler's run: A3's growth with the field's spacing, then a certified sweep. Only
// rectangles (no torus) and only a3, which is the algorithm it generalises.
int RunGenerateField(const GenerateArguments& arguments, const RadiusFieldSpec& spec,
                     const Rect& domain, uint64_t seed) {
  if (Status status = CheckFieldAlgorithm(arguments.field, arguments.algorithm); !status.ok()) {
    return ReportBadArguments("generate", status);
  }
  if (arguments.torus) {
    return ReportBadArguments("generate",
                              InvalidArgument("--torus: a radius field samples rectangles only"));
  }
  StatusOr<RadiusField> field = RadiusField::Create(spec);
  if (!field.ok()) return ReportBadArguments("generate", field.status());
  FieldSampleStats stats;
  const auto start = std::chrono::steady_clock::now();
  StatusOr<std::vector<Vec2>> points =
      SampleField({.domain = domain, .seed = seed}, *field, &stats);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!points.ok()) return ReportBadArguments("generate", points.status());
  WritePoints(std::cout, arguments.format, *points, {}, RadiiAt(&*field, *points), domain, {});
  if (arguments.stats) {
    std::cerr << std::setprecision(6) << "algorithm a3\nfield "
              << RadiusFieldKindName(field->kind()) << "\ncount " << points->size() << "\ngrown "
              << stats.grown << "\nswept " << stats.swept << "\nseconds " << seconds
              << "\npoints_per_second " << static_cast<double>(points->size()) / seconds << '\n';
  }
  return 0;
}

// The layered run: the layers (and their seeds, generation order and exclusion matrix) are a
// layered world's, sampled on the domain alone rather than queried from the plane. Only
// rectangles, and only a3, by which every layer after the first grows.
int RunGenerateLayers(const GenerateArguments& arguments, const Rect& domain, uint64_t seed) {
  if (arguments.algorithm != "a3") {
    return ReportBadArguments("generate",
                              InvalidArgument("--algorithm: layers are sampled by a3 only, got '" +
                                              arguments.algorithm + "'"));
  }
  if (arguments.torus) {
    return ReportBadArguments("generate",
                              InvalidArgument("--torus: layers sample rectangles only"));
  }
  StatusOr<std::vector<LayerSpec>> layers = ParseLayers(arguments.layers);
  if (!layers.ok()) return ReportBadArguments("generate", layers.status());
  StatusOr<std::vector<LayerExclusionSpec>> exclusions = ParseExclusions(arguments.layers);
  if (!exclusions.ok()) return ReportBadArguments("generate", exclusions.status());
  StatusOr<World> world = World::Create(
      {.seed = seed, .layers = std::move(*layers), .exclusions = std::move(*exclusions)});
  if (!world.ok()) return ReportBadArguments("generate", world.status());
  StatusOr<LayerMask> shown = ParseLayerFilter(arguments.layers, *world);
  if (!shown.ok()) return ReportBadArguments("generate", shown.status());
  const auto start = std::chrono::steady_clock::now();
  StatusOr<LayeredPoints> sampled = SampleLayers(BoundedLayersOn(*world->layers(), domain));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!sampled.ok()) return ReportBadArguments("generate", sampled.status());
  LayeredPoints printed;
  for (size_t k = 0; k < sampled->positions.size(); ++k) {
    if ((*shown >> sampled->layers[k] & 1) == 0) continue;
    printed.positions.push_back(sampled->positions[k]);
    printed.layers.push_back(sampled->layers[k]);
  }
  const std::vector<std::string> names = LayerNames(*world);
  WritePoints(std::cout, arguments.format, printed.positions, {},
              LayerRadiiAt(*world, printed.positions, printed.layers,
                           arguments.format == PointFormat::kSvg),
              domain, {}, {.of = printed.layers, .names = names});
  if (arguments.stats) {
    std::cerr << std::setprecision(6) << "algorithm a3\nlayers " << names.size() << "\ncount "
              << sampled->positions.size() << "\nseconds " << seconds << "\npoints_per_second "
              << static_cast<double>(sampled->positions.size()) / seconds << '\n';
  }
  return 0;
}

int RunGenerate(const GenerateArguments& arguments) {
  SamplerOptions options;
  auto algorithm = ParseAlgorithm(arguments.algorithm);
  if (!algorithm.ok()) return ReportBadArguments("generate", algorithm.status());
  auto domain = ParseRect(arguments.domain, "--domain");
  if (!domain.ok()) return ReportBadArguments("generate", domain.status());
  options.algorithm = *algorithm;
  options.domain = {*domain, arguments.torus};
  options.min_distance = arguments.min_distance;
  options.density = arguments.density;
  auto seed = ParseSeed(arguments.seed);
  if (!seed.ok()) return ReportBadArguments("generate", seed.status());
  options.seed = *seed;
  StatusOr<std::optional<RadiusFieldSpec>> field = ParseLocalField(arguments.field);
  if (!field.ok()) return ReportBadArguments("generate", field.status());
  if (field->has_value()) return RunGenerateField(arguments, **field, *domain, *seed);
  if (HasLayers(arguments.layers)) return RunGenerateLayers(arguments, *domain, *seed);
  if (!arguments.layers.filter.empty()) {
    return ReportBadArguments("generate", InvalidArgument("--layers: needs --layer"));
  }
  options.dart_failure_limit = arguments.dart_failure_limit;
  options.dart_exhaustive = arguments.dart_exhaustive;

  const auto start = std::chrono::steady_clock::now();
  auto points = Sample(options);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!points.ok()) return ReportBadArguments("generate", points.status());
  WritePoints(std::cout, arguments.format, *points, {}, {}, options.domain.rect,
              {.seam_spacing = 0.0, .dot_radius = options.min_distance / 2});
  if (arguments.stats) {
    const auto rho = NormalisedRadius(static_cast<int64_t>(points->size()),
                                      options.domain.rect.Area(), options.min_distance);
    std::cerr << std::setprecision(6) << "algorithm " << AlgorithmName(options.algorithm)
              << "\ncount " << points->size() << "\nrho " << (rho.ok() ? *rho : NAN) << "\nseconds "
              << seconds << "\npoints_per_second " << static_cast<double>(points->size()) / seconds
              << '\n';
  }
  return 0;
}

}  // namespace

CommandRunner RegisterGenerate(CLI::App& app) {
  auto arguments = std::make_shared<GenerateArguments>();
  CLI::App* command = app.add_subcommand("generate", "Sample a bounded domain with one algorithm");
  command
      ->add_option("--algorithm", arguments->algorithm,
                   "a1, a2, a3, dart, best-candidate or bridson")
      ->capture_default_str();
  command
      ->add_option("--min-distance", arguments->min_distance, "Minimum distance d between points")
      ->capture_default_str();
  command->add_option("--domain", arguments->domain, "Rectangle X0,Y0,X1,Y1 (half-open)")
      ->capture_default_str();
  command->add_flag("--torus", arguments->torus, "Wrap the domain's opposite edges");
  command
      ->add_option("--density", arguments->density,
                   "r'/2r in (1, 2] for a1 and a2; a1 at 2 is exact dart throwing")
      ->capture_default_str();
  command->add_option("--seed", arguments->seed, "Random seed, 0..2^64-1")
      ->type_name("UINT")
      ->capture_default_str();
  AddFormatOption(*command, arguments->format);
  command->add_flag("--stats", arguments->stats,
                    "Print count, rho, seconds and points per second to stderr");
  command
      ->add_option("--dart-failure-limit", arguments->dart_failure_limit,
                   "dart: stop after this many misses in a row")
      ->capture_default_str();
  command->add_flag("--dart-exhaustive", arguments->dart_exhaustive,
                    "dart: run until no spot is left (maximal)");
  AddFieldOptions(*command, arguments->field);
  AddLayerOptions(*command, arguments->layers);
  return [arguments] { return RunGenerate(*arguments); };
}

}  // namespace scallop::cli
