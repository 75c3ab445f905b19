// `scallop nearest`: the cellular-noise basis (nearest point id, F1, F2 and
// the nearest point) at positions read as `x,y` lines, computed locally by a
// NearestLookup or, with --server, by scallopd's Nearest in batches of at
// most the server's max_nearest_batch. Both print the same CSV, bit for bit.
#include <CLI/CLI.hpp>
#include <charconv>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "client/commands/command_exit.h"
#include "client/commands/commands.h"
#include "client/options/remote_options.h"
#include "client/options/world_options.h"
#include "scallop/noise/nearest_lookup.h"

namespace scallop::cli {
namespace {

struct NearestArguments {
  WorldArguments world;
  RemoteArguments remote;  // with --server, scallopd answers instead
  std::string input = "-";
};

std::string_view Trimmed(std::string_view text) {
  const size_t first = text.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

// Reads `x,y` lines. Blank lines and lines starting with '#' are skipped, and
// so is a first line "x,y" (a header). Errors name the line.
StatusOr<std::vector<Vec2>> ReadPositions(std::istream& in) {
  std::vector<Vec2> positions;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::string_view text = Trimmed(line);
    if (text.empty() || text.front() == '#') continue;
    if (positions.empty() && text == "x,y") continue;
    const size_t comma = text.find(',');
    double values[2] = {0, 0};
    const std::string_view parts[2] = {
        Trimmed(text.substr(0, comma)),
        comma == std::string_view::npos ? std::string_view{} : Trimmed(text.substr(comma + 1))};
    for (int axis = 0; axis < 2; ++axis) {
      const auto [end, error] = std::from_chars(
          parts[axis].data(), parts[axis].data() + parts[axis].size(), values[axis]);
      if (parts[axis].empty() || error != std::errc() ||
          end != parts[axis].data() + parts[axis].size() || !std::isfinite(values[axis])) {
        return InvalidArgument("input line " + std::to_string(number) +
                               ": expected x,y (two finite numbers), got '" + std::string(text) +
                               "'");
      }
    }
    positions.push_back({values[0], values[1]});
  }
  if (in.bad()) return InvalidArgument("input: read error");
  return positions;
}

void WriteCsv(std::ostream& out, const std::vector<Vec2>& positions,
              const std::vector<NearestPoint>& results) {
  out << std::setprecision(17) << "x,y,id,f1,f2,nearest_x,nearest_y\n";
  for (size_t k = 0; k < positions.size(); ++k) {
    const NearestPoint& n = results[k];
    out << positions[k].x << ',' << positions[k].y << ',' << n.id << ',' << n.f1 << ',' << n.f2
        << ',' << n.position.x << ',' << n.position.y << '\n';
  }
}

int RunLocal(const NearestArguments& arguments, const std::vector<Vec2>& positions,
             std::vector<NearestPoint>& results) {
  StatusOr<World> parsed = ParseWorld(arguments.world);
  if (!parsed.ok()) return ReportBadArguments("nearest", parsed.status());
  StatusOr<World> world = NoiseBasisWorld(arguments.world.layers, *parsed);
  if (!world.ok()) return ReportBadArguments("nearest", world.status());
  StatusOr<PlaneEngineOptions> engine_options = ParseEngineOptions(arguments.world);
  if (!engine_options.ok()) return ReportBadArguments("nearest", engine_options.status());
  PlaneEngine engine(*engine_options);
  NearestLookup lookup(engine);
  // Positions are numbered in input order, skipped lines aside.
  if (Status status = lookup.Nearest(*world, positions, results); !status.ok()) {
    return ReportBadArguments("nearest", status);
  }
  return 0;
}

int RunRemote(const NearestArguments& arguments, const std::vector<Vec2>& positions,
              std::vector<NearestPoint>& results) {
  v1::NearestRequest request;
  if (Status status = SetRequestWorld(arguments.remote, arguments.world, request); !status.ok()) {
    return ReportBadArguments("nearest", status);
  }
  StatusOr<std::string> layer = SingleLayerName(arguments.world.layers);
  if (!layer.ok()) return ReportBadArguments("nearest", layer.status());
  request.set_layer(*layer);
  StatusOr<client::ScallopClient> connected =
      ConnectTo(arguments.remote.server, arguments.remote.connection);
  if (!connected.ok()) return ReportBadArguments("nearest", connected.status());
  client::ScallopClient& client = *connected;
  const client::CallOptions options = CallOptionsFor(arguments.remote);
  v1::GetServerInfoResponse info;
  if (grpc::Status status = client.GetServerInfo(info, options); !status.ok()) {
    return ReportCallFailure("nearest", status);
  }
  const size_t batch = static_cast<size_t>(std::max(1, info.limits().max_nearest_batch()));
  for (size_t first = 0; first < positions.size(); first += batch) {
    const size_t count = std::min(batch, positions.size() - first);
    request.mutable_positions()->clear_xs();
    request.mutable_positions()->clear_ys();
    for (size_t k = first; k < first + count; ++k) {
      request.mutable_positions()->add_xs(positions[k].x);
      request.mutable_positions()->add_ys(positions[k].y);
    }
    v1::NearestResponse response;
    if (grpc::Status status = client.Nearest(request, response, options); !status.ok()) {
      // The server numbers positions within the batch.
      return ReportCallFailure(
          "nearest",
          {status.error_code(), status.error_message() + " (in the batch starting at position " +
                                    std::to_string(first) + ")"});
    }
    const auto n = static_cast<int>(count);
    if (response.ids_size() != n || response.f1_size() != n || response.f2_size() != n ||
        response.nearest_xs_size() != n || response.nearest_ys_size() != n ||
        response.cell_values_size() != n) {
      return ReportCallFailure("nearest", {grpc::StatusCode::INTERNAL,
                                           "malformed reply: arrays do not match the batch"});
    }
    for (int k = 0; k < n; ++k) {
      results[first + k] = {.id = response.ids(k),
                            .position = {response.nearest_xs(k), response.nearest_ys(k)},
                            .f1 = response.f1(k),
                            .f2 = response.f2(k),
                            .second_id = 0,
                            .cell_value = response.cell_values(k)};
    }
  }
  return 0;
}

int RunNearest(const NearestArguments& arguments) {
  StatusOr<std::vector<Vec2>> positions = InvalidArgument("");
  if (arguments.input == "-") {
    positions = ReadPositions(std::cin);
  } else {
    std::ifstream file(arguments.input);
    if (!file) {
      return ReportBadArguments("nearest",
                                InvalidArgument("--input: cannot open '" + arguments.input + "'"));
    }
    positions = ReadPositions(file);
  }
  if (!positions.ok()) return ReportBadArguments("nearest", positions.status());
  std::vector<NearestPoint> results(positions->size());
  const int code = arguments.remote.server.empty() ? RunLocal(arguments, *positions, results)
                                                   : RunRemote(arguments, *positions, results);
  if (code != 0) return code;
  WriteCsv(std::cout, *positions, results);
  return 0;
}

}  // namespace

CommandRunner RegisterNearest(CLI::App& app) {
  auto arguments = std::make_shared<NearestArguments>();
  CLI::App* command =
      app.add_subcommand("nearest", "Nearest point id, F1 and F2 at positions (x,y lines), as CSV");
  AddWorldOptions(*command, arguments->world, /*with_rect=*/false);
  AddRemoteOptions(*command, arguments->remote, /*server_optional=*/true);
  command->add_option("--input", arguments->input, "File of x,y lines; - for stdin")
      ->capture_default_str();
  return [arguments] { return RunNearest(*arguments); };
}

}  // namespace scallop::cli
