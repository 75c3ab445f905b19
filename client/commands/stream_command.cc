// `scallop stream`: a rectangle of a world from scallopd's StreamPoints. CSV is
// written chunk by chunk as it arrives, so memory stays bounded; JSON and SVG
// are whole documents and are written at the end.
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

struct StreamArguments {
  WorldArguments world;
  RemoteArguments remote;
  PointFormat format = PointFormat::kCsv;
  bool seams = false;
  v1::PointEncoding encoding = v1::POINT_ENCODING_UNSPECIFIED;
};

int RunStream(const StreamArguments& arguments) {
  v1::StreamPointsRequest request;
  if (Status status = SetRequestWorldAndRect(arguments.remote, arguments.world, request);
      !status.ok()) {
    return ReportBadArguments("stream", status);
  }
  SetRequestLayerFilter(arguments.world, request);
  request.set_encoding(arguments.encoding);
  StatusOr<client::ScallopClient> connected =
      ConnectTo(arguments.remote.server, arguments.remote.connection);
  if (!connected.ok()) return ReportBadArguments("stream", connected.status());
  client::ScallopClient& client = *connected;
  const client::CallOptions options = CallOptionsFor(arguments.remote);
  PlanePoints points;
  std::vector<double> radii;
  const bool incremental_csv = arguments.format == PointFormat::kCsv;
  IncrementalCsv csv(std::cout, request.world().has_radius_field(),
                     LayerNamesFrom(client, request, options));
  Status malformed;
  const grpc::Status status = client.StreamPoints(
      request,
      [&](const v1::PointsChunk& chunk) {
        if (!incremental_csv) {
          malformed = ReadPoints(chunk.points(), points, &radii);
          return malformed.ok();
        }
        StatusOr<int> written = csv.Write(chunk.points());
        if (!written.ok()) malformed = written.status();
        return written.ok();
      },
      options);
  if (!status.ok()) return ReportCallFailure("stream", status);
  if (!malformed.ok())
    return ReportCallFailure("stream", {grpc::StatusCode::INTERNAL, malformed.message()});
  if (incremental_csv) {
    csv.Finish();
    return 0;
  }
  if (grpc::Status written = WriteRemotePoints(client, request, options, arguments.format,
                                               arguments.seams, points, radii, std::cout);
      !written.ok()) {
    return ReportCallFailure("stream", written);
  }
  return 0;
}

}  // namespace

CommandRunner RegisterStream(CLI::App& app) {
  auto arguments = std::make_shared<StreamArguments>();
  CLI::App* command =
      app.add_subcommand("stream", "A rectangle of a world, from scallopd (streamed by region)");
  AddWorldOptions(*command, arguments->world);
  AddRemoteOptions(*command, arguments->remote);
  AddFormatAndSeamsOptions(*command, arguments->format, arguments->seams);
  AddEncodingOption(*command, arguments->encoding);
  return [arguments] { return RunStream(*arguments); };
}

}  // namespace scallop::cli
