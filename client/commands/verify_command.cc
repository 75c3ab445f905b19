// `scallop verify`: checks the contract (spacing and maximality) on one
// rectangle of a world, locally or with --server through scallopd's Verify,
// and reports what it measured, as text or JSON (the same for both paths).
#include <CLI/CLI.hpp>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "client/commands/command_exit.h"
#include "client/commands/commands.h"
#include "client/options/remote_options.h"
#include "client/options/world_options.h"
#include "client/output/point_output.h"
#include "scallop/plane/world_verifier.h"
#include "verify_messages.h"

namespace scallop::cli {
namespace {

// The verifier holds about 250 bytes per point (delaunay_verifier.h), so the
// engine's 1e8 d^2 (85M points, 21 GB) is too much: 1e7 d^2 is 8.5M points,
// about 2.3 GB and 35 s (1e6 d^2 takes 3.5 s and 230 MB on two cores).
constexpr QueryLimit kVerifyLimit{.max_area = 1e7, .name = "scallop verify's limit"};

struct VerifyArguments {
  WorldArguments world;
  RemoteArguments remote;  // with --server, scallopd verifies instead
  bool json = false;
};

// JSON has no infinity (what the report holds when nothing was measured): null instead.
nlohmann::json Measured(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

// The world as the report names it: from the World locally, from the answer's message remotely
// (where a raster field's pixels are the server's, so no World can be made of it).
struct VerifiedWorld {
  std::string description;
  nlohmann::json json;
  double d = 1.0;
  std::vector<std::string> layer_names;  // a layered world's, in its layers' order
};

VerifiedWorld VerifiedWorldOf(const World& world) {
  VerifiedWorld verified{world.Describe(),
                         {{"seed", world.seed()},
                          {"min_distance", world.min_distance()},
                          {"algorithm", WorldAlgorithmName(world.algorithm())},
                          {"density", world.density()},
                          {"generator_version", world.generator_version()}},
                         world.min_distance(),
                         LayerNames(world)};
  if (!verified.layer_names.empty()) verified.json["layers"] = verified.layer_names;
  return verified;
}

nlohmann::json FieldJson(const FieldVerifyReport& field) {
  return {{"conflicts", field.conflicts},
          {"min_spacing_ratio", Measured(field.min_spacing_ratio)},
          {"largest_gap", Measured(field.largest_gap)},
          {"largest_gap_spot", {field.largest_gap_spot.x, field.largest_gap_spot.y}},
          {"gap_bound", Measured(field.gap_bound)},
          {"points_masked", field.points_masked},
          {"passed", field.passed()}};
}

// Per layer, by name: its own report (conflicts within it, gaps given the others); and the
// pairs across layers.
nlohmann::json LayeredJson(const LayerVerifyReport& layered,
                           const std::vector<std::string>& names) {
  nlohmann::json layers = nlohmann::json::object();
  for (size_t k = 0; k < layered.layers.size(); ++k) {
    layers[names[k]] = FieldJson(layered.layers[k]);
    layers[names[k]]["points_checked"] = layered.layers[k].points_checked;
  }
  return {{"layers", layers},
          {"cross_pairs_checked", layered.cross_pairs_checked},
          {"cross_conflicts", layered.cross_conflicts},
          {"min_cross_ratio", Measured(layered.min_cross_ratio)},
          {"passed", layered.passed()}};
}

void WriteJsonReport(std::ostream& out, const VerifiedWorld& world, const Rect& rect,
                     const VerifyReport& report) {
  const double d = world.d;
  nlohmann::json document{
      {"world", world.json},
      {"rect", {rect.x0, rect.y0, rect.x1, rect.y1}},
      {"points_checked", report.points_checked},
      {"pairs_checked", report.pairs_checked},
      {"pairs_across_seams", report.pairs_across_seams},
      {"min_distance", Measured(report.min_distance)},
      {"min_distance_over_d", Measured(report.min_distance / d)},
      {"min_distance_across_seams", Measured(report.min_distance_across_seams)},
      {"min_distance_across_seams_over_d", Measured(report.min_distance_across_seams / d)},
      {"largest_empty_circle", Measured(report.largest_empty_circle)},
      {"largest_empty_circle_over_d", Measured(report.largest_empty_circle / d)},
      {"largest_empty_centre", {report.largest_empty_centre.x, report.largest_empty_centre.y}},
      {"spacing_violations", report.spacing_violations},
      {"spacing_violations_across_seams", report.spacing_violations_across_seams},
      {"spacing_ok", report.spacing_ok},
      {"maximal_ok", report.maximal_ok},
      {"passed", report.passed()}};
  if (report.field) document["field"] = FieldJson(*report.field);
  if (report.layered) document["layered"] = LayeredJson(*report.layered, world.layer_names);
  out << document.dump() << '\n';
}

// "1.00000000023 (1.00000000023 d)", or "none" when no pair was measured.
std::string WithRatio(double value, double d) {
  if (!std::isfinite(value)) return "none";
  std::ostringstream text;
  // 12 digits show the spacing margin, d * 2^-32, above d.
  text << std::setprecision(12) << value << " (" << value / d << " d)";
  return text.str();
}

void WriteTextReport(std::ostream& out, const VerifiedWorld& world, const Rect& r,
                     const VerifyReport& report) {
  const double d = world.d;
  out << std::setprecision(12);
  out << "world                      " << world.description << '\n'
      << "rect                       " << r.x0 << ',' << r.y0 << ',' << r.x1 << ',' << r.y1 << '\n'
      << "points checked             " << report.points_checked << '\n'
      << "pairs checked              " << report.pairs_checked << '\n'
      << "pairs across seams         " << report.pairs_across_seams << '\n'
      << "min distance               " << WithRatio(report.min_distance, d) << '\n'
      << "min distance across seams  " << WithRatio(report.min_distance_across_seams, d) << '\n'
      << "largest empty circle       " << WithRatio(report.largest_empty_circle, d) << " at ("
      << report.largest_empty_centre.x << ", " << report.largest_empty_centre.y << ")\n"
      << "spacing                    " << (report.spacing_ok ? "ok" : "FAILED") << " ("
      << report.spacing_violations << " violations, " << report.spacing_violations_across_seams
      << " across seams)\n"
      << "maximality                 " << (report.maximal_ok ? "ok" : "FAILED") << '\n';
  if (report.field) {
    const FieldVerifyReport& field = *report.field;
    out << "field conflicts            " << field.conflicts << " (smallest |p-q| / max R "
        << field.min_spacing_ratio << ")\n"
        << "field largest gap          " << field.largest_gap << " at (" << field.largest_gap_spot.x
        << ", " << field.largest_gap_spot.y << "), certified below " << field.gap_bound << '\n'
        << "points in masks            " << field.points_masked << '\n';
  }
  if (report.layered) {
    const LayerVerifyReport& layered = *report.layered;
    for (size_t k = 0; k < layered.layers.size(); ++k) {
      const FieldVerifyReport& layer = layered.layers[k];
      out << "layer " << world.layer_names[k] << ": " << layer.points_checked << " points, "
          << layer.conflicts << " conflicts (smallest |p-q| / rule " << layer.min_spacing_ratio
          << "), largest gap given the others " << layer.largest_gap << ", certified below "
          << layer.gap_bound << ", " << (layer.passed() ? "ok" : "FAILED") << '\n';
    }
    out << "pairs across layers        " << layered.cross_pairs_checked << ", "
        << layered.cross_conflicts << " closer than D (smallest |p-q| / D "
        << layered.min_cross_ratio << ")\n";
  }
  out << "result                     " << (report.passed() ? "pass" : "FAIL") << '\n';
}

// The server's report in the core's shape, so both paths print alike.
VerifyReport ReportFromMessage(const v1::VerifyResponse& response) {
  VerifyReport report;
  report.points_checked = response.points_checked();
  report.pairs_checked = response.pairs_checked();
  report.min_distance = response.min_distance();
  report.spacing_violations = response.spacing_violations();
  report.largest_empty_circle = response.largest_empty_circle();
  report.largest_empty_centre = {response.largest_empty_centre_x(),
                                 response.largest_empty_centre_y()};
  report.pairs_across_seams = response.pairs_across_seams();
  report.min_distance_across_seams = response.min_distance_across_seams();
  report.spacing_violations_across_seams = response.spacing_violations_across_seams();
  report.spacing_ok = response.spacing_ok();
  report.maximal_ok = response.maximal_ok();
  if (response.has_field()) {
    report.field = FieldVerifyFromMessage(response.field(), response.maximal_ok());
  }
  if (response.has_layered()) report.layered = LayeredVerifyFromMessage(response.layered());
  return report;
}

int RunRemoteVerify(const VerifyArguments& arguments) {
  v1::VerifyRequest request;
  if (Status status = SetRequestWorldAndRect(arguments.remote, arguments.world, request);
      !status.ok()) {
    return ReportBadArguments("verify", status);
  }
  StatusOr<client::ScallopClient> connected =
      ConnectTo(arguments.remote.server, arguments.remote.connection);
  if (!connected.ok()) return ReportBadArguments("verify", connected.status());
  client::ScallopClient& client = *connected;
  v1::VerifyResponse response;
  if (grpc::Status status = client.Verify(request, response, CallOptionsFor(arguments.remote));
      !status.ok()) {
    return ReportCallFailure("verify", status);
  }
  const v1::World& message = response.world();
  VerifiedWorld world;
  if (StatusOr<World> parsed = WorldFromMessage(message); parsed.ok()) {
    world = VerifiedWorldOf(*parsed);
  } else if (message.radius_field().has_raster()) {
    // The raster is the server's: the world is named by its parameters and the raster's name.
    world = {"seed=" + std::to_string(message.seed()) + " algorithm=a3 field=raster raster=" +
                 message.radius_field().raster().raster_name(),
             {{"seed", message.seed()},
              {"min_distance", message.min_distance()},
              {"raster_name", message.radius_field().raster().raster_name()}},
             message.min_distance(),
             {}};
  } else if (message.layers_size() != 0) {
    // A layer's raster is the server's: the world is named by its seed and its layers' names.
    world = {
        "seed=" + std::to_string(message.seed()) + " layers=[", {}, message.min_distance(), {}};
    for (const v1::Layer& layer : message.layers()) {
      world.description += (world.layer_names.empty() ? "" : " ") + layer.name();
      world.layer_names.push_back(layer.name());
    }
    world.description += "]";
    world.json = {{"seed", message.seed()},
                  {"min_distance", message.min_distance()},
                  {"layers", world.layer_names}};
  } else {
    return ReportCallFailure("verify", {grpc::StatusCode::INTERNAL, parsed.status().message()});
  }
  const Rect rect = RectFromMessage(request.rect());
  const VerifyReport report = ReportFromMessage(response);
  if (arguments.json) {
    WriteJsonReport(std::cout, world, rect, report);
  } else {
    WriteTextReport(std::cout, world, rect, report);
  }
  return response.passed() ? 0 : 1;
}

int RunVerify(const VerifyArguments& arguments) {
  if (!arguments.remote.server.empty()) return RunRemoteVerify(arguments);
  StatusOr<WorldQuery> query = ParseWorldQuery(arguments.world);
  if (!query.ok()) return ReportBadArguments("verify", query.status());
  query->engine.max_query_area = kVerifyLimit.max_area;
  PlaneEngine engine(query->engine);
  // VerifyWorldRect checks the rectangle and the one grown by its halo
  // first: failures there are the caller's, so exit 2.
  StatusOr<VerifyReport> report = VerifyWorldRect(engine, query->world, query->rect, kVerifyLimit);
  if (!report.ok()) return ReportBadArguments("verify", report.status());
  const VerifiedWorld world = VerifiedWorldOf(query->world);
  if (arguments.json) {
    WriteJsonReport(std::cout, world, query->rect, *report);
  } else {
    WriteTextReport(std::cout, world, query->rect, *report);
  }
  return report->passed() ? 0 : 1;
}

}  // namespace

CommandRunner RegisterVerify(CLI::App& app) {
  auto arguments = std::make_shared<VerifyArguments>();
  CLI::App* command =
      app.add_subcommand("verify", "Check spacing and maximality on a rectangle of a world");
  AddWorldOptions(*command, arguments->world);
  AddRemoteOptions(*command, arguments->remote, /*server_optional=*/true);
  command->add_flag("--json", arguments->json, "Print the report as one JSON object");
  return [arguments] { return RunVerify(*arguments); };
}

}  // namespace scallop::cli
