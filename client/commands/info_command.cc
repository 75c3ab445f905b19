// `scallop info`: what a scallopd serves: its version, limits, worlds, health,
// and one world described (--world NAME, the inline world options, or the
// server's default when neither is given).
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "client/commands/command_exit.h"
#include "client/commands/commands.h"
#include "client/options/remote_options.h"

namespace scallop::cli {
namespace {

struct InfoArguments {
  WorldArguments world;
  RemoteArguments remote;
  bool json = false;
  bool inline_world = false;  // any of the inline world's options given
};

int RunInfo(const InfoArguments& arguments) {
  v1::DescribeWorldRequest describe;
  if (!arguments.remote.world_name.empty() || arguments.inline_world) {
    if (Status status = SetRequestWorld(arguments.remote, arguments.world, describe);
        !status.ok()) {
      return ReportBadArguments("info", status);
    }
  }
  StatusOr<client::ScallopClient> connected =
      ConnectTo(arguments.remote.server, arguments.remote.connection);
  if (!connected.ok()) return ReportBadArguments("info", connected.status());
  client::ScallopClient& client = *connected;
  const client::CallOptions options = CallOptionsFor(arguments.remote);
  v1::GetServerInfoResponse info;
  if (grpc::Status status = client.GetServerInfo(info, options); !status.ok()) {
    return ReportCallFailure("info", status);
  }
  v1::DescribeWorldResponse world;
  if (grpc::Status status = client.DescribeWorld(describe, world, options); !status.ok()) {
    return ReportCallFailure("info", status);
  }
  bool serving = false;
  if (grpc::Status status = client.CheckHealth(serving, options); !status.ok()) {
    return ReportCallFailure("info", status);
  }
  const v1::Limits& limits = info.limits();
  const std::vector<std::string> names(info.world_names().begin(), info.world_names().end());
  const std::vector<std::string> descriptions(info.world_descriptions().begin(),
                                              info.world_descriptions().end());
  nlohmann::json rasters = nlohmann::json::array();
  for (const v1::RasterInfo& raster : info.rasters()) {
    rasters.push_back({{"name", raster.name()},
                       {"width", raster.width()},
                       {"height", raster.height()},
                       {"bit_depth", raster.bit_depth()},
                       {"pixel_hash", raster.pixel_hash()}});
  }
  if (arguments.json) {
    const nlohmann::json document{{"serving", serving},
                                  {"generator_version", info.generator_version()},
                                  {"region_side_in_d", info.region_side_in_d()},
                                  {"field_region_side_in_r_max", info.field_region_side_in_r_max()},
                                  {"precision_range_in_d", info.precision_range_in_d()},
                                  {"limits",
                                   {{"max_page_size", limits.max_page_size()},
                                    {"max_query_area", limits.max_query_area()},
                                    {"max_stream_area", limits.max_stream_area()},
                                    {"max_verify_area", limits.max_verify_area()},
                                    {"max_in_flight", limits.max_in_flight()},
                                    {"max_nearest_batch", limits.max_nearest_batch()},
                                    {"max_noise_grid_samples", limits.max_noise_grid_samples()},
                                    {"max_follow_area", limits.max_follow_area()},
                                    {"max_nearest_regions", limits.max_nearest_regions()},
                                    {"max_streams_in_flight", limits.max_streams_in_flight()},
                                    {"stream_stall_seconds", limits.stream_stall_seconds()},
                                    {"follow_stall_seconds", limits.follow_stall_seconds()},
                                    {"follow_idle_seconds", limits.follow_idle_seconds()}}},
                                  {"default_world", info.default_world()},
                                  {"worlds", names},
                                  {"world_descriptions", descriptions},
                                  {"rasters", rasters},
                                  {"world",
                                   {{"name", world.name()},
                                    {"description", world.description()},
                                    {"region_side", world.region_side()},
                                    {"precision_limit", world.precision_limit()},
                                    {"fingerprint", world.fingerprint()},
                                    {"field_kind", world.field_kind()},
                                    {"r_min", world.r_min()},
                                    {"r_max", world.r_max()}}}};
    std::cout << document.dump() << '\n';
    return 0;
  }
  std::cout << "health              " << (serving ? "SERVING" : "NOT_SERVING") << '\n'
            << "generator version   " << info.generator_version() << '\n'
            << "region side         " << info.region_side_in_d()
            << " d (radius fields: " << info.field_region_side_in_r_max() << " r_max)\n"
            << "precision range     |x|, |y| <= " << info.precision_range_in_d() << " d\n"
            << "max page size       " << limits.max_page_size() << " points\n"
            << "max query area      " << limits.max_query_area() << " d^2 (GetPoints)\n"
            << "max stream area     " << limits.max_stream_area() << " d^2 (StreamPoints)\n"
            << "max verify area     " << limits.max_verify_area() << " d^2 (Verify)\n"
            << "max in flight       " << limits.max_in_flight() << " unary calls\n"
            << "max streams         " << limits.max_streams_in_flight() << " streaming calls\n"
            << "max nearest batch   " << limits.max_nearest_batch() << " positions\n"
            << "max noise grid      " << limits.max_noise_grid_samples() << " samples\n"
            << "max nearest regions " << limits.max_nearest_regions()
            << " regions (Nearest, NoiseGrid)\n"
            << "max follow area     " << limits.max_follow_area() << " d^2 (Follow)\n"
            << "stall / idle        " << limits.stream_stall_seconds() << " s (StreamPoints), "
            << limits.follow_stall_seconds() << " s / " << limits.follow_idle_seconds()
            << " s (Follow)\n"
            << "default world       " << info.default_world() << '\n'
            << "worlds             ";
  for (const std::string& name : names) std::cout << ' ' << name;
  std::cout << '\n';
  for (const v1::RasterInfo& raster : info.rasters()) {
    std::cout << "raster              " << raster.name() << ": " << raster.width() << " x "
              << raster.height() << ", " << raster.bit_depth() << " bit, pixel hash " << std::hex
              << raster.pixel_hash() << std::dec << '\n';
  }
  std::cout << "world               " << (world.name().empty() ? "(inline)" : world.name()) << ": "
            << world.description() << '\n'
            << "  region side       " << world.region_side() << '\n'
            << "  precision limit   " << world.precision_limit() << '\n';
  if (world.field_kind() != "constant") {
    std::cout << "  radius field      " << world.field_kind() << ", R in [" << world.r_min() << ", "
              << world.r_max() << "]; limits in units of r_min\n";
  }
  return 0;
}

}  // namespace

CommandRunner RegisterInfo(CLI::App& app) {
  auto arguments = std::make_shared<InfoArguments>();
  CLI::App* command = app.add_subcommand("info", "What a scallopd serves, and one world");
  AddWorldOptions(*command, arguments->world, /*with_rect=*/false);
  AddRemoteOptions(*command, arguments->remote);
  command->add_flag("--json", arguments->json, "Print one JSON object");
  return [arguments, command] {
    for (const char* option : {"--seed", "--min-distance", "--algorithm", "--density",
                               "--radius-noise", "--radius-raster"}) {
      if (command->count(option) > 0) arguments->inline_world = true;
    }
    return RunInfo(*arguments);
  };
}

}  // namespace scallop::cli
