// Request validation and message conversion of every RPC, as scallopd applies
// them, on request messages parsed from arbitrary bytes: the first byte picks
// the RPC, the rest is parsed as its request proto. Each request goes through
// the checks its RPC runs before any work (ServiceContext::ResolveQuery, the
// world registry, the rectangle rule, the Nearest and NoiseGrid position and
// region bounds, Follow's viewport rule, page tokens). Invariants:
//   - a refusal has a message naming a field or setting ("name: ...");
//   - an accepted world converts to a message and back to the same world;
//   - an accepted rectangle round-trips through its message bit for bit;
//   - an accepted GetPoints rectangle small enough to generate cheaply
//     (kGenerateSide) yields points inside it, which survive the trip
//     through a Points message and back, in the request's encoding too
//     (exact: bit for bit; quantised: the same ids), with their layers (a
//     layered world's, under the request's layer filter).
#include <boost/asio/thread_pool.hpp>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "encoded_points.h"
#include "fuzz/fuzz_check.h"
#include "noise_messages.h"
#include "scallop/noise/noise_grid.h"
#include "scallop/plane/layer_regions.h"
#include "scallop/plane/viewport_tracker.h"
#include "server/layer_choice.h"
#include "server/service_context.h"
#include "world_messages.h"

namespace scallop::server {
namespace {

// GetPoints rectangles up to this side (in d) are generated: at most 9
// regions. (An area bound would let a 1e-3 d x 78,000 d sliver through, and
// its 5,000 regions take seconds under the sanitizers.)
constexpr double kGenerateSide = 32;

// The configuration a fuzzed server runs with: the defaults, plus a named
// world of another density, so world_name reaches more than one world.
ServerConfig FuzzConfig() {
  ServerConfig config;
  config.worlds.emplace("sparse", *World::Create({.seed = 7, .min_distance = 2, .density = 1}));
  // A layered world, so `layers` filters and per-layer answers are reached by name.
  config.worlds.emplace("forest",
                        *World::Create({.seed = 7,
                                        .layers = {{.name = "trees", .min_distance = 8},
                                                   {.name = "rocks", .min_distance = 2}}}));
  return config;
}

struct FuzzService {
  ServerConfig config = FuzzConfig();
  WorldRegistry worlds{config.worlds, config.default_world};
  PageTokenCodec page_tokens{"scallop-fuzz-page-token-key"};
  PlaneEngine engine{{.cache_bytes = 16 << 20, .threads = 1, .max_query_area = 1e8}};
  boost::asio::thread_pool pool{1};
  ServiceContext shared{config, worlds, page_tokens, engine, pool, nullptr, nullptr};
};

FuzzService& Service() {
  static FuzzService* service = new FuzzService;  // never destroyed: no exit-time races
  return *service;
}

// "field: ..." or "field.sub: ...": the API's promise that an error names
// what was wrong.
void CheckNamesField(const grpc::Status& status, const char* rpc) {
  const std::string& message = status.error_message();
  const size_t colon = message.find(": ");
  SCALLOP_FUZZ_CHECK(!status.ok() && colon != std::string::npos && colon > 0,
                     std::string(rpc) + " refusal without a field name: " + message);
}

template <typename Request>
void CheckRefusalOrWorld(const Request& request, const grpc::Status& status, const char* rpc) {
  if (!status.ok()) return CheckNamesField(status, rpc);
  ResolvedWorld resolved;
  SCALLOP_FUZZ_CHECK(Service().worlds.Resolve(request, resolved).ok(), rpc);
  const StatusOr<World> again = WorldFromMessage(WorldToMessage(resolved.world));
  SCALLOP_FUZZ_CHECK(
      again.ok() && again->fingerprint() == resolved.world.fingerprint(),
      std::string(rpc) + ": world does not round-trip: " + resolved.world.Describe());
}

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void CheckRectRoundTrip(const Rect& rect) {
  const Rect back = RectFromMessage(RectToMessage(rect));
  SCALLOP_FUZZ_CHECK(SameBits(back.x0, rect.x0) && SameBits(back.y0, rect.y0) &&
                         SameBits(back.x1, rect.x1) && SameBits(back.y1, rect.y1),
                     "rect does not round-trip");
}

void FuzzGetPoints(const v1::GetPointsRequest& request) {
  FuzzService& service = Service();
  RequestLog log("GetPoints");
  World world;
  Rect rect;
  grpc::Status status = service.shared.ResolveQuery(request, service.config.max_query_area,
                                                    "max_query_area", log, world, rect);
  if (status.ok() && !request.page_token().empty()) {
    status = ToGrpcStatus(service.page_tokens.Decode(request.page_token(), world, rect).status());
  }
  CheckRefusalOrWorld(request, status, "GetPoints");
  if (!status.ok()) return;
  const StatusOr<PointEncoding> encoding = PointEncodingFromMessage(request.encoding());
  if (!encoding.ok()) return CheckNamesField(ToGrpcStatus(encoding.status()), "GetPoints");
  LayerMask layers = kAllLayers;
  if (grpc::Status filter = LayerFilterOf(world, request.layers(), "layers", layers);
      !filter.ok()) {
    return CheckNamesField(filter, "GetPoints");
  }
  CheckRectRoundTrip(rect);
  // A layered world generates every layer's regions, the smallest layer's many: smaller sides.
  const double side =
      (world.layers() != nullptr ? kGenerateSide / 4 : kGenerateSide) * world.min_distance();
  if (!(rect.Width() <= side && rect.Height() <= side)) return;
  StatusOr<PlanePoints> points = service.engine.Points(world, rect, layers);
  SCALLOP_FUZZ_CHECK(points.ok(), "an accepted rectangle fails: " + points.status().message());
  v1::Points message;
  AppendPoints(*points, 0, points->positions.size(), message, world, PointEncoding::kPacked);
  PlanePoints back;
  SCALLOP_FUZZ_CHECK(
      ReadPoints(message, back).ok() && back.ids == points->ids && back.layers == points->layers,
      "points do not round-trip");
  for (const Vec2& p : back.positions) {
    SCALLOP_FUZZ_CHECK(p.x >= rect.x0 && p.x < rect.x1 && p.y >= rect.y0 && p.y < rect.y1,
                       "a point outside its rectangle");
  }
  // The encoding asked for (docs/wire.md): exact gives the same bits, any
  // gives the same ids.
  v1::Points encoded;
  AppendPoints(*points, 0, points->positions.size(), encoded, world, *encoding);
  PlanePoints decoded;
  SCALLOP_FUZZ_CHECK(ReadPoints(encoded, decoded).ok() && decoded.ids == points->ids &&
                         decoded.layers == points->layers,
                     "encoded points do not round-trip");
  if (*encoding == PointEncoding::kQuantised) return;
  for (size_t k = 0; k < decoded.positions.size(); ++k) {
    SCALLOP_FUZZ_CHECK(SameBits(decoded.positions[k].x, points->positions[k].x) &&
                           SameBits(decoded.positions[k].y, points->positions[k].y),
                       "an exact encoding changed a coordinate");
  }
}

template <typename Request>
void FuzzRectQuery(const Request& request, double max_area, const char* limit, const char* rpc) {
  RequestLog log(rpc);
  World world;
  Rect rect;
  const grpc::Status status =
      Service().shared.ResolveQuery(request, max_area, limit, log, world, rect);
  CheckRefusalOrWorld(request, status, rpc);
  if (status.ok()) CheckRectRoundTrip(rect);
}

void FuzzNearest(const v1::NearestRequest& request) {
  FuzzService& service = Service();
  ResolvedWorld resolved;
  grpc::Status status = service.worlds.Resolve(request, resolved);
  const v1::Positions& message = request.positions();
  if (status.ok() && (message.xs_size() != message.ys_size() ||
                      message.xs_size() > service.config.max_nearest_batch)) {
    return;  // refused by the RPC itself with a "positions: ..." message
  }
  int layer = -1;
  if (status.ok()) status = LayerChoiceOf(resolved.world, request.layer(), "layer", layer);
  const World& world = status.ok() ? WorldOfLayer(resolved.world, layer) : resolved.world;
  std::vector<Vec2> positions;
  for (int k = 0; status.ok() && k < message.xs_size(); ++k) {
    positions.push_back({message.xs(k), message.ys(k)});
    status = ToGrpcStatus(NearestLookup::ValidatePosition(world, positions.back(), k));
  }
  if (status.ok()) {
    status = service.shared.CheckNearestRegions(
        world, NearestLookup::CountRegions(world, positions), "positions", "split");
  }
  CheckRefusalOrWorld(request, status, "Nearest");
}

void FuzzNoiseGrid(const v1::NoiseGridRequest& request) {
  FuzzService& service = Service();
  ResolvedWorld resolved;
  grpc::Status status = service.worlds.Resolve(request, resolved);
  const std::optional<NoiseChannel> channel = NoiseChannelFromMessage(request.channel());
  if (!status.ok() || !channel) return CheckRefusalOrWorld(request, status, "NoiseGrid");
  SCALLOP_FUZZ_CHECK(NoiseChannelToMessage(*channel) == request.channel(),
                     "noise channel does not round-trip");
  const NoiseGridSpec spec{.origin = {request.origin_x(), request.origin_y()},
                           .step = request.step(),
                           .width = request.width(),
                           .height = request.height(),
                           .channel = *channel};
  status =
      ToGrpcStatus(ValidateNoiseGrid(resolved.world, spec, service.config.max_noise_grid_samples));
  if (status.ok()) {
    status =
        service.shared.CheckNearestRegions(resolved.world, NoiseGridRegions(resolved.world, spec),
                                           "step: the samples", "use a smaller step");
  }
  CheckRefusalOrWorld(request, status, "NoiseGrid");
}

void FuzzFollow(const v1::FollowRequest& request) {
  FuzzService& service = Service();
  ResolvedWorld resolved;
  grpc::Status status = service.worlds.Resolve(request, resolved);
  if (status.ok() && request.has_viewport()) {
    // The message as follow_rpc.cc reads it.
    ViewportUpdate update{.viewport = RectFromMessage(request.viewport()),
                          .velocity = {request.velocity_x(), request.velocity_y()},
                          .keep_margin = request.keep_margin()};
    for (const v1::RegionKey& key : request.held_regions()) {
      update.held_regions.push_back({key.i(), key.j()});
    }
    status = ToGrpcStatus(
        ValidateViewportUpdate(resolved.world, update, service.config.max_follow_area));
  }
  CheckRefusalOrWorld(request, status, "Follow");
}

template <typename Request>
bool Parse(const uint8_t* data, size_t size, Request& request) {
  return request.ParseFromArray(data, static_cast<int>(size));
}

}  // namespace
}  // namespace scallop::server

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace scallop;
  using namespace scallop::server;
  if (size == 0) return 0;
  const uint8_t rpc = data[0] % 7;
  ++data;
  --size;
  switch (rpc) {
    case 0: {
      v1::GetPointsRequest request;
      if (Parse(data, size, request)) FuzzGetPoints(request);
      break;
    }
    case 1: {
      v1::StreamPointsRequest request;
      if (Parse(data, size, request)) {
        FuzzRectQuery(request, Service().config.max_stream_area, "max_stream_area", "StreamPoints");
      }
      break;
    }
    case 2: {
      v1::VerifyRequest request;
      if (Parse(data, size, request)) {
        FuzzRectQuery(request, Service().config.max_verify_area, "max_verify_area", "Verify");
      }
      break;
    }
    case 3: {
      v1::NearestRequest request;
      if (Parse(data, size, request)) FuzzNearest(request);
      break;
    }
    case 4: {
      v1::NoiseGridRequest request;
      if (Parse(data, size, request)) FuzzNoiseGrid(request);
      break;
    }
    case 5: {
      v1::FollowRequest request;
      if (Parse(data, size, request)) FuzzFollow(request);
      break;
    }
    default: {
      v1::DescribeWorldRequest request;
      if (Parse(data, size, request)) {
        ResolvedWorld resolved;
        CheckRefusalOrWorld(request, Service().worlds.Resolve(request, resolved), "DescribeWorld");
      }
      break;
    }
  }
  return 0;
}
