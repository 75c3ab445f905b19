// `scallop plane`: prints one rectangle of an infinite world, each point with
// its id, computed locally by a PlaneEngine.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "client/commands/command_exit.h"
#include "client/commands/commands.h"
#include "client/options/format_options.h"
#include "client/options/world_options.h"
#include "client/output/point_output.h"
#include "scallop/plane/region_layout.h"

namespace scallop::cli {
namespace {

struct PlaneArguments {
  WorldArguments world;
  PointFormat format = PointFormat::kCsv;
  bool seams = false;
};

int RunPlane(const PlaneArguments& arguments) {
  StatusOr<WorldQuery> query = ParseWorldQuery(arguments.world);
  if (!query.ok()) return ReportBadArguments("plane", query.status());
  PlaneEngine engine(query->engine);
  // Points runs PlaneEngine::ValidateQuery first, so bad rectangles end here.
  StatusOr<PlanePoints> points = engine.Points(query->world, query->rect, query->layers);
  if (!points.ok()) return ReportBadArguments("plane", points.status());
  const World& world = query->world;
  // Seams every region side (16 d; a field world's 6 r_max).
  const SvgStyle style{.seam_spacing = arguments.seams ? RegionLayout(world).side() : 0.0,
                       .dot_radius = world.min_distance() / 2};
  if (world.layers() != nullptr) {
    // Layered: the layer column, each layer's colour, and disks at half each point's spacing.
    const std::vector<std::string> names = LayerNames(world);
    const std::vector<double> radii = LayerRadiiAt(world, points->positions, points->layers,
                                                   arguments.format == PointFormat::kSvg);
    WritePoints(std::cout, arguments.format, points->positions, points->ids, radii, query->rect,
                style, {points->layers, names});
    return 0;
  }
  WritePoints(std::cout, arguments.format, points->positions, points->ids,
              RadiiAt(world.radius_field(), points->positions), query->rect, style);
  return 0;
}

}  // namespace

CommandRunner RegisterPlane(CLI::App& app) {
  auto arguments = std::make_shared<PlaneArguments>();
  CLI::App* command = app.add_subcommand("plane", "Print a rectangle of an infinite world");
  AddWorldOptions(*command, arguments->world);
  AddFormatAndSeamsOptions(*command, arguments->format, arguments->seams);
  return [arguments] { return RunPlane(*arguments); };
}

}  // namespace scallop::cli
