// `scallop noise`: one channel of the cellular-noise basis sampled at the
// pixel centres of --size over --rect, rendered as a PNG (north up),
// computed locally or, with --server, by scallopd's NoiseGrid.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "client/commands/command_exit.h"
#include "client/commands/commands.h"
#include "client/options/rect_option.h"
#include "client/options/remote_options.h"
#include "client/options/world_options.h"
#include "noise_messages.h"
#include "scallop/image/png_image.h"
#include "scallop/noise/noise_grid.h"
#include "scallop/random/rng.h"

namespace scallop::cli {
namespace {

// 16M samples: 128 MB of values, a few seconds of lookups.
constexpr int64_t kMaxLocalSamples = int64_t{1} << 24;

struct NoiseArguments {
  WorldArguments world;
  RemoteArguments remote;  // with --server, scallopd evaluates the grid
  std::string size;
  std::string channel = "f1";
  std::string png;
};

// "WxH": two integers >= 1.
StatusOr<std::pair<int, int>> ParseSize(const std::string& text) {
  int width = 0, height = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%dx%d%c", &width, &height, &tail) != 2 || width < 1 ||
      height < 1) {
    return InvalidArgument("--size: expected WxH with W, H >= 1, got '" + text + "'");
  }
  return std::pair{width, height};
}

// Samples at pixel centres: square pixels, so --size must have --rect's aspect.
StatusOr<NoiseGridSpec> ParseSpec(const NoiseArguments& arguments, const Rect& rect) {
  StatusOr<std::pair<int, int>> size = ParseSize(arguments.size);
  if (!size.ok()) return size.status();
  StatusOr<NoiseChannel> channel = ParseNoiseChannel(arguments.channel);
  if (!channel.ok()) return InvalidArgument("--" + channel.status().message());
  const auto [width, height] = *size;
  const double step = rect.Width() / width;
  if (std::abs(rect.Height() / height - step) > 1e-9 * step) {
    return InvalidArgument("--size: " + arguments.size +
                           " pixels are not square over --rect; make W / H equal the "
                           "rectangle's width / height");
  }
  return NoiseGridSpec{.origin = {rect.x0 + step / 2, rect.y0 + step / 2},
                       .step = step,
                       .width = width,
                       .height = height,
                       .channel = *channel};
}

// The largest spacing of the world an answer names: d, or r_max with a
// radius field (the distances' scale, docs/noise.md).
// A world's (or with `layer`, that layer's) largest spacing as the message gives it.
double LargestSpacing(const v1::World& world, const std::string& layer = {}) {
  for (const v1::Layer& own : world.layers()) {
    if (own.name() != layer) continue;
    if (own.radius_field().has_noise()) return own.radius_field().noise().r_max();
    if (own.radius_field().has_raster()) return own.radius_field().raster().r_max();
    return own.min_distance();
  }
  if (world.radius_field().has_noise()) return world.radius_field().noise().r_max();
  if (world.radius_field().has_raster()) return world.radius_field().raster().r_max();
  return world.min_distance();
}

// Grey for the distances and the cell value, a colour per point for ids.
// Row 0 of the image is the top: the grid's last row. d is the world's
// largest spacing (r_max with a field), which bounds F1 and F2 / 2.
Image8 Render(const NoiseImage& noise, NoiseChannel channel, double d) {
  Image8 image{.width = noise.width,
               .height = noise.height,
               .channels = channel == NoiseChannel::kId ? 3 : 1,
               .pixels = {}};
  image.pixels.resize(static_cast<size_t>(noise.width) * noise.height * image.channels);
  double high = 1;  // cell values lie in [0, 1)
  if (channel == NoiseChannel::kF1 || channel == NoiseChannel::kF2MinusF1) high = d;
  if (channel == NoiseChannel::kF2) high = 2 * d;  // F2 < 2 d on a maximal set
  for (int r = 0; r < noise.height; ++r) {
    for (int c = 0; c < noise.width; ++c) {
      const size_t sample = static_cast<size_t>(r) * noise.width + c;
      const size_t pixel =
          (static_cast<size_t>(noise.height - 1 - r) * noise.width + c) * image.channels;
      if (channel == NoiseChannel::kId) {
        const uint64_t colour = Mix64(noise.ids[sample]);
        for (int k = 0; k < 3; ++k)
          image.pixels[pixel + k] = static_cast<uint8_t>(colour >> (8 * k));
      } else {
        image.pixels[pixel] = GreyLevel(noise.values[sample], 0, high);
      }
    }
  }
  return image;
}

int RunNoise(const NoiseArguments& arguments) {
  StatusOr<Rect> rect = ParseRect(arguments.world.rect, "--rect");
  if (!rect.ok()) return ReportBadArguments("noise", rect.status());
  StatusOr<NoiseGridSpec> spec = ParseSpec(arguments, *rect);
  if (!spec.ok()) return ReportBadArguments("noise", spec.status());

  NoiseImage noise;
  double d = arguments.world.min_distance;
  if (arguments.remote.server.empty()) {
    StatusOr<WorldQuery> query = ParseWorldQuery(arguments.world);
    if (!query.ok()) return ReportBadArguments("noise", query.status());
    PlaneEngine engine(query->engine);
    NearestLookup lookup(engine);
    StatusOr<World> world = NoiseBasisWorld(arguments.world.layers, query->world);
    if (!world.ok()) return ReportBadArguments("noise", world.status());
    StatusOr<NoiseImage> image = EvaluateNoiseGrid(lookup, *world, *spec, kMaxLocalSamples);
    if (!image.ok()) return ReportBadArguments("noise", image.status());
    noise = std::move(*image);
    d = world->max_spacing();
  } else {
    v1::NoiseGridRequest request;
    if (Status status = SetRequestWorld(arguments.remote, arguments.world, request); !status.ok()) {
      return ReportBadArguments("noise", status);
    }
    request.set_origin_x(spec->origin.x);
    request.set_origin_y(spec->origin.y);
    request.set_step(spec->step);
    request.set_width(spec->width);
    request.set_height(spec->height);
    request.set_channel(NoiseChannelToMessage(spec->channel));
    StatusOr<std::string> layer = SingleLayerName(arguments.world.layers);
    if (!layer.ok()) return ReportBadArguments("noise", layer.status());
    request.set_layer(*layer);
    StatusOr<client::ScallopClient> connected =
        ConnectTo(arguments.remote.server, arguments.remote.connection);
    if (!connected.ok()) return ReportBadArguments("noise", connected.status());
    client::ScallopClient& client = *connected;
    v1::NoiseGridResponse response;
    if (grpc::Status status = client.NoiseGrid(request, response, CallOptionsFor(arguments.remote));
        !status.ok()) {
      return ReportCallFailure("noise", status);
    }
    const size_t samples = static_cast<size_t>(spec->width) * spec->height;
    const bool ids = spec->channel == NoiseChannel::kId;
    if (static_cast<size_t>(ids ? response.ids_size() : response.values_size()) != samples) {
      return ReportCallFailure(
          "noise", {grpc::StatusCode::INTERNAL, "malformed reply: wrong number of samples"});
    }
    noise = {.width = spec->width,
             .height = spec->height,
             .values = {response.values().begin(), response.values().end()},
             .ids = {response.ids().begin(), response.ids().end()}};
    d = LargestSpacing(response.world(), request.layer());
  }
  if (Status status = WritePng(arguments.png, Render(noise, spec->channel, d)); !status.ok()) {
    return ReportBadArguments("noise", status);
  }
  return 0;
}

}  // namespace

CommandRunner RegisterNoise(CLI::App& app) {
  auto arguments = std::make_shared<NoiseArguments>();
  CLI::App* command =
      app.add_subcommand("noise", "Render a cellular-noise channel of a world as a PNG image");
  AddWorldOptions(*command, arguments->world);
  AddRemoteOptions(*command, arguments->remote, /*server_optional=*/true);
  command->add_option("--size", arguments->size, "Image size WxH in pixels (square pixels)")
      ->required();
  command->add_option("--channel", arguments->channel, "f1, f2, f2-f1, id or cell")
      ->capture_default_str();
  command->add_option("--png", arguments->png, "Output PNG file")->required();
  return [arguments] { return RunNoise(*arguments); };
}

}  // namespace scallop::cli
