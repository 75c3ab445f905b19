// `scallop generate`: runs one bounded-domain sampler locally and prints its
// points, with optional statistics on stderr. With a radius field (--radius-noise,
// --radius-raster) the sampler is the field sampler (SampleField), and each point carries R.
// With layers (--layer, --exclusion) every layer is sampled on the domain (SampleLayers), and
// each point carries its layer. --world-file samples a YAML world's spec the same way.
#include <CLI/CLI.hpp>
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
  std::string world_file;  // instead of the world's options: a YAML world (world_options.h)
};

Status CheckRectanglesByA3(const GenerateArguments& arguments, const std::string& what) {
  if (arguments.algorithm != "a3") {
    return InvalidArgument("--algorithm: " + what + " sampled by a3 only, got '" +
                           arguments.algorithm + "'");
  }
  if (arguments.torus) return InvalidArgument("--torus: " + what + " sampled on rectangles only");
  return Status::Ok();
}

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The field sampler's run: A3's growth with the field's spacing, then a certified sweep.
int RunGenerateField(const GenerateArguments& arguments, const RadiusField& field,
                     const Rect& domain, uint64_t seed) {
  FieldSampleStats stats;
  const auto start = std::chrono::steady_clock::now();
  StatusOr<std::vector<Vec2>> points = SampleField({.domain = domain, .seed = seed}, field, &stats);
  const double seconds = SecondsSince(start);
  if (!points.ok()) return ReportBadArguments("generate", points.status());
  WritePoints(std::cout, arguments.format, *points, {}, RadiiAt(&field, *points), domain, {});
  if (arguments.stats) {
    std::cerr << std::setprecision(6) << "algorithm a3\nfield " << RadiusFieldKindName(field.kind())
              << "\ncount " << points->size() << "\ngrown " << stats.grown << "\nswept "
              << stats.swept << "\nseconds " << seconds << "\npoints_per_second "
              << static_cast<double>(points->size()) / seconds << '\n';
  }
  return 0;
}

// The layered run: the layers (and their seeds, generation order and exclusion matrix) are a
// layered world's, sampled on the domain alone rather than queried from the plane.
int RunGenerateLayers(const GenerateArguments& arguments, const World& world, const Rect& domain) {
  StatusOr<LayerMask> shown = ParseLayerFilter(arguments.layers, world);
  if (!shown.ok()) return ReportBadArguments("generate", shown.status());
  const auto start = std::chrono::steady_clock::now();
  StatusOr<LayeredPoints> sampled = SampleLayers(BoundedLayersOn(*world.layers(), domain));
  const double seconds = SecondsSince(start);
  if (!sampled.ok()) return ReportBadArguments("generate", sampled.status());
  LayeredPoints printed;
  for (size_t k = 0; k < sampled->positions.size(); ++k) {
    if ((*shown >> sampled->layers[k] & 1) == 0) continue;
    printed.positions.push_back(sampled->positions[k]);
    printed.layers.push_back(sampled->layers[k]);
  }
  const std::vector<std::string> names = LayerNames(world);
  WritePoints(
      std::cout, arguments.format, printed.positions, {},
      LayerRadiiAt(world, printed.positions, printed.layers, arguments.format == PointFormat::kSvg),
      domain, {}, {.of = printed.layers, .names = names});
  if (arguments.stats) {
    std::cerr << std::setprecision(6) << "algorithm a3\nlayers " << names.size() << "\ncount "
              << sampled->positions.size() << "\nseconds " << seconds << "\npoints_per_second "
              << static_cast<double>(sampled->positions.size()) / seconds << '\n';
  }
  return 0;
}

// One algorithm at one spacing.
int RunGenerateSample(const GenerateArguments& arguments, SamplerOptions options) {
  options.dart_failure_limit = arguments.dart_failure_limit;
  options.dart_exhaustive = arguments.dart_exhaustive;
  const auto start = std::chrono::steady_clock::now();
  auto points = Sample(options);
  const double seconds = SecondsSince(start);
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

// --world-file: the file's world sampled on the domain alone, as the flags would give it: its
// layers, its field, or its algorithm, spacing and density; the file's seed.
int RunGenerateWorldFile(const GenerateArguments& arguments, const Rect& domain) {
  WorldArguments file;
  file.world_file = arguments.world_file;
  StatusOr<World> world = ParseWorld(file);
  if (!world.ok()) return ReportBadArguments("generate", world.status());
  const std::string what = "--world-file " + arguments.world_file + ": ";
  if (world->layers() != nullptr || world->radius_field() != nullptr) {
    if (arguments.torus) {
      return ReportBadArguments(
          "generate", InvalidArgument("--torus: " + what + "layers and fields sample rectangles"));
    }
    if (world->layers() != nullptr) return RunGenerateLayers(arguments, *world, domain);
    return RunGenerateField(arguments, *world->radius_field(), domain, world->seed());
  }
  if (!arguments.layers.filter.empty()) {
    return ReportBadArguments("generate",
                              InvalidArgument("--layers: " + what + "the world has no layers"));
  }
  StatusOr<Algorithm> algorithm = ParseAlgorithm(WorldAlgorithmName(world->algorithm()));
  if (!algorithm.ok()) return ReportBadArguments("generate", algorithm.status());
  return RunGenerateSample(arguments, {.algorithm = *algorithm,
                                       .domain = {domain, arguments.torus},
                                       .min_distance = world->min_distance(),
                                       .density = world->density(),
                                       .seed = world->seed()});
}

int RunGenerate(const GenerateArguments& arguments) {
  auto domain = ParseRect(arguments.domain, "--domain");
  if (!domain.ok()) return ReportBadArguments("generate", domain.status());
  if (!arguments.world_file.empty()) return RunGenerateWorldFile(arguments, *domain);
  auto algorithm = ParseAlgorithm(arguments.algorithm);
  if (!algorithm.ok()) return ReportBadArguments("generate", algorithm.status());
  auto seed = ParseSeed(arguments.seed);
  if (!seed.ok()) return ReportBadArguments("generate", seed.status());
  StatusOr<std::optional<RadiusFieldSpec>> field = ParseLocalField(arguments.field);
  if (!field.ok()) return ReportBadArguments("generate", field.status());
  if (field->has_value()) {
    Status status = CheckFieldAlgorithm(arguments.field, arguments.algorithm);
    if (status.ok()) status = CheckRectanglesByA3(arguments, "a radius field is");
    if (!status.ok()) return ReportBadArguments("generate", status);
    StatusOr<RadiusField> made = RadiusField::Create(**field);
    if (!made.ok()) return ReportBadArguments("generate", made.status());
    return RunGenerateField(arguments, *made, *domain, *seed);
  }
  if (HasLayers(arguments.layers)) {
    if (Status status = CheckRectanglesByA3(arguments, "layers are"); !status.ok()) {
      return ReportBadArguments("generate", status);
    }
    StatusOr<std::vector<LayerSpec>> layers = ParseLayers(arguments.layers);
    if (!layers.ok()) return ReportBadArguments("generate", layers.status());
    StatusOr<std::vector<LayerExclusionSpec>> exclusions = ParseExclusions(arguments.layers);
    if (!exclusions.ok()) return ReportBadArguments("generate", exclusions.status());
    StatusOr<World> world = World::Create(
        {.seed = *seed, .layers = std::move(*layers), .exclusions = std::move(*exclusions)});
    if (!world.ok()) return ReportBadArguments("generate", world.status());
    return RunGenerateLayers(arguments, *world, *domain);
  }
  if (!arguments.layers.filter.empty()) {
    return ReportBadArguments("generate", InvalidArgument("--layers: needs --layer"));
  }
  return RunGenerateSample(arguments, {.algorithm = *algorithm,
                                       .domain = {*domain, arguments.torus},
                                       .min_distance = arguments.min_distance,
                                       .density = arguments.density,
                                       .seed = *seed});
}

}  // namespace

CommandRunner RegisterGenerate(CLI::App& app) {
  auto arguments = std::make_shared<GenerateArguments>();
  CLI::App* command = app.add_subcommand(
      "generate", "Sample a bounded domain: one algorithm, a radius field or layers");
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
  CLI::Option* file = command->add_option(
      "--world-file", arguments->world_file,
      "A world as YAML (the keys of a named world in scallopd's config), sampled on the domain "
      "alone: its layers, its field, or its algorithm and spacing, with its seed");
  file->type_name("FILE");
  ExcludeWorldOptions(*file, *command);
  return [arguments] { return RunGenerate(*arguments); };
}

}  // namespace scallop::cli
