// `scallop follow`: replays a path of viewports (one X0,Y0,X1,Y1 per line)
// through scallopd's Follow. Every point received goes to stdout as the
// `id,x,y` CSV of `scallop plane`; points, bytes, messages, evictions and the
// time from sending a step to its last message go to stderr, one line a step.
#include <CLI/CLI.hpp>
#include <chrono>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "client/commands/command_exit.h"
#include "client/commands/commands.h"
#include "client/options/rect_option.h"
#include "client/options/remote_options.h"
#include "client/output/remote_points_output.h"
#include "follow_client.h"

namespace scallop::cli {
namespace {

struct FollowArguments {
  WorldArguments world;
  RemoteArguments remote;
  std::string path;
  double keep_margin = 0;
  v1::PointEncoding encoding = v1::POINT_ENCODING_UNSPECIFIED;
};

// The path's rectangles; blank lines and lines starting with '#' are skipped.
StatusOr<std::vector<Rect>> ReadPath(const std::string& file) {
  std::ifstream in(file);
  if (!in) return InvalidArgument("--path: cannot read '" + file + "'");
  std::vector<Rect> path;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.empty() || line[0] == '#') continue;
    StatusOr<Rect> rect = ParseRect(line, "--path line " + std::to_string(number));
    if (!rect.ok()) return rect.status();
    path.push_back(*rect);
  }
  if (path.empty()) return InvalidArgument("--path: '" + file + "' has no rectangle");
  return path;
}

int RunFollow(const FollowArguments& arguments) {
  v1::FollowRequest first;
  if (Status status = SetRequestWorld(arguments.remote, arguments.world, first); !status.ok()) {
    return ReportBadArguments("follow", status);
  }
  first.set_encoding(arguments.encoding);
  SetRequestLayerFilter(arguments.world, first);
  StatusOr<std::vector<Rect>> path = ReadPath(arguments.path);
  if (!path.ok()) return ReportBadArguments("follow", path.status());
  StatusOr<client::ScallopClient> connected =
      ConnectTo(arguments.remote.server, arguments.remote.connection);
  if (!connected.ok()) return ReportBadArguments("follow", connected.status());
  client::ScallopClient& client = *connected;
  client::FollowSession session(client, CallOptionsFor(arguments.remote));
  IncrementalCsv csv(std::cout, first.world().has_radius_field(),
                     LayerNamesFrom(client, first, CallOptionsFor(arguments.remote)));
  int64_t total_points = 0, total_bytes = 0;
  for (size_t step = 0; step < path->size(); ++step) {
    v1::FollowRequest request = step == 0 ? first : v1::FollowRequest();
    *request.mutable_viewport() = RectToMessage((*path)[step]);
    request.set_keep_margin(arguments.keep_margin);
    int64_t points = 0, bytes = 0, messages = 0, evicted = 0;
    Status malformed;
    const auto start = std::chrono::steady_clock::now();
    const grpc::Status status = session.Update(request, [&](const v1::FollowResponse& response) {
      ++messages;
      bytes += static_cast<int64_t>(response.ByteSizeLong());
      evicted += response.evicted_size();
      StatusOr<int> written = csv.Write(response.chunk().points());
      if (written.ok()) {
        points += *written;
      } else if (malformed.ok()) {
        malformed = written.status();
      }
    });
    const double milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (!status.ok()) return ReportCallFailure("follow", status);
    if (!malformed.ok()) {
      return ReportCallFailure("follow", {grpc::StatusCode::INTERNAL, malformed.message()});
    }
    total_points += points;
    total_bytes += bytes;
    std::cerr << "step " << step + 1 << ": " << points << " points, " << bytes << " bytes, "
              << messages << " messages, " << evicted << " regions evicted, " << std::fixed
              << std::setprecision(3) << milliseconds << " ms\n"
              << std::defaultfloat;
  }
  if (grpc::Status status = session.Finish(); !status.ok()) {
    return ReportCallFailure("follow", status);
  }
  csv.Finish();
  std::cerr << "total: " << path->size() << " steps, " << total_points << " points, " << total_bytes
            << " bytes\n";
  return 0;
}

}  // namespace

CommandRunner RegisterFollow(CLI::App& app) {
  auto arguments = std::make_shared<FollowArguments>();
  CLI::App* command = app.add_subcommand(
      "follow", "Replay a path of viewports through scallopd's Follow (points newly in view)");
  AddWorldOptions(*command, arguments->world, /*with_rect=*/false);
  AddRemoteOptions(*command, arguments->remote);
  command->add_option("--path", arguments->path, "File of viewports, one X0,Y0,X1,Y1 a line")
      ->required();
  command
      ->add_option("--keep-margin", arguments->keep_margin,
                   "Keep regions within this distance of the viewport (world units)")
      ->capture_default_str();
  AddEncodingOption(*command, arguments->encoding);
  return [arguments] { return RunFollow(*arguments); };
}

}  // namespace scallop::cli
