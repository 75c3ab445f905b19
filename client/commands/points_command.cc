// `scallop points`: a rectangle of a world from scallopd's GetPoints, page by
// page, printed as `scallop plane` prints it.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "client/commands/command_exit.h"
#include "client/commands/commands.h"
#include "client/options/format_options.h"
#include "client/options/remote_options.h"
#include "client/output/remote_points_output.h"

namespace scallop::cli {
namespace {

struct PointsArguments {
  WorldArguments world;
  RemoteArguments remote;
  PointFormat format = PointFormat::kCsv;
  bool seams = false;
  int page_size = 0;
  v1::PointEncoding encoding = v1::POINT_ENCODING_UNSPECIFIED;
};

int RunPoints(const PointsArguments& arguments) {
  v1::GetPointsRequest request;
  if (Status status = SetRequestWorldAndRect(arguments.remote, arguments.world, request);
      !status.ok()) {
    return ReportBadArguments("points", status);
  }
  SetRequestLayerFilter(arguments.world, request);
  request.set_page_size(arguments.page_size);
  request.set_encoding(arguments.encoding);
  StatusOr<client::ScallopClient> connected =
      ConnectTo(arguments.remote.server, arguments.remote.connection);
  if (!connected.ok()) return ReportBadArguments("points", connected.status());
  client::ScallopClient& client = *connected;
  const client::CallOptions options = CallOptionsFor(arguments.remote);
  PlanePoints points;
  std::vector<double> radii;
  if (grpc::Status status = client.GetAllPoints(request, points, options, &radii); !status.ok()) {
    return ReportCallFailure("points", status);
  }
  if (grpc::Status status = WriteRemotePoints(client, request, options, arguments.format,
                                              arguments.seams, points, radii, std::cout);
      !status.ok()) {
    return ReportCallFailure("points", status);
  }
  return 0;
}

}  // namespace

CommandRunner RegisterPoints(CLI::App& app) {
  auto arguments = std::make_shared<PointsArguments>();
  CLI::App* command = app.add_subcommand("points", "A rectangle of a world, from scallopd (paged)");
  AddWorldOptions(*command, arguments->world);
  AddRemoteOptions(*command, arguments->remote);
  AddFormatAndSeamsOptions(*command, arguments->format, arguments->seams);
  command->add_option("--page-size", arguments->page_size, "Points per page (0: server's maximum)")
      ->check(CLI::NonNegativeNumber);
  AddEncodingOption(*command, arguments->encoding);
  return [arguments] { return RunPoints(*arguments); };
}

}  // namespace scallop::cli
