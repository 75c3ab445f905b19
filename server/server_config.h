// scallopd's configuration: built-in defaults, then an optional YAML file,
// then command-line flags, each overriding the one before.
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "raster_catalog.h"
#include "scallop/base/status.h"
#include "scallop/plane/world.h"

namespace scallop::server {

struct ServerConfig {
  std::string listen = "127.0.0.1:50051";  // HOST:PORT; port 0 picks a free one
  std::string metrics_listen;              // HOST:PORT of GET /metrics (Prometheus); empty: off
  // HOST:PORT of the HTTP tiles, world list and viewer (docs/tiles.md); empty: off.
  std::string http_listen;
  int threads = 2;                // request threads, and as many generating regions
  int64_t cache_megabytes = 512;  // region cache budget (about 32 bytes a point)
  int32_t max_page_size = 65536;  // points per GetPoints page (1.5 MB)
  double max_query_area = 1e6;    // GetPoints, in d^2 (about 850k points)
  double max_stream_area = 1e8;   // StreamPoints, in d^2
  double max_verify_area = 1e6;   // Verify, in d^2 (about 3.5 s on two cores)
  int max_in_flight = 64;         // concurrent unary calls before RESOURCE_EXHAUSTED
  // Streaming calls count apart, so idle streams cannot take every unary
  // slot and a burst of unary calls cannot starve the streams.
  int max_streams_in_flight = 32;
  // 24 bytes in and 48 out a position: 2^16 positions is 3 MB of answer.
  int32_t max_nearest_batch = 1 << 16;  // positions per Nearest call
  // width * height per NoiseGrid call: 8 bytes a sample, 500,000 is 4 MB,
  // under gRPC's default 4 MiB (4,194,304 bytes) with room for the envelope.
  int64_t max_noise_grid_samples = 500000;
  // Distinct regions a Nearest call's positions (or a NoiseGrid's samples)
  // may lie in. A cold region costs a search grid, about 2.5 ms on two
  // threads: 4,096 regions is about 10 s cold, a 1,024 d square.
  int64_t max_nearest_regions = 4096;
  double max_follow_area = 1e5;      // Follow viewport grown by keep_margin, in d^2
  double follow_stall_seconds = 10;  // a Follow client not reading is dropped after this
  double follow_idle_seconds = 300;  // a Follow client sending no update is dropped after this
  double stream_stall_seconds = 10;  // a StreamPoints client not reading is dropped after this
  // Connections the metrics listener serves at once; more are closed at once.
  int max_metrics_connections = 16;
  // Connections the HTTP listener (http_listen) serves at once; more are closed at once.
  int max_http_connections = 256;
  // Cache-Control max-age of tiles. Worlds never change, so a year; lower it
  // only if a world's name may come to mean another world.
  int64_t http_max_age_seconds = 31536000;
  // Share the listening port with other processes (SO_REUSEPORT). Off: a
  // second server on a port in use fails to start instead of splitting calls.
  bool reuse_port = false;
  double grace_seconds = 10;  // in-flight requests get this long after SIGTERM
  double drain_seconds = 0;   // NOT_SERVING this long before refusing new calls
  // debug, info (a line per call), warn (failed calls only), error or off.
  std::string log_level = "info";
  // Key for page tokens. Empty: derived from the world set (see page_token.h).
  std::string page_token_secret;
  // TLS (tls_credentials.h): PEM files of the server's certificate chain and
  // key; both or neither. With tls_client_ca, mutual TLS: clients must show a
  // certificate that CA signs. Empty: plaintext.
  std::string tls_cert;
  std::string tls_key;
  std::string tls_client_ca;
  // Bearer tokens, one a line (token_table.h). Empty: no token needed.
  std::string auth_tokens;
  // Serve gRPC reflection (what lets grpcurl list the API). Off hides the
  // API's shape from whoever can reach the port; the health check stays.
  bool reflection = true;
  // Limits no one client can exhaust alone (admission_budget.h, rate_limiter.h).
  // Regions the unary calls in flight may touch in all: 16 of the largest
  // square GetPoints (about 4,000 regions each).
  int64_t max_in_flight_cost = 65536;
  // What one client may hold of max_in_flight, max_in_flight_cost and
  // max_streams_in_flight.
  double max_client_share = 0.5;
  // Calls a second per client, in bursts of rate_limit_burst; 0: no limit.
  // Off by default: behind a proxy every client is the proxy (client_key.h).
  double rate_limit_per_second = 0;
  double rate_limit_burst = 100;
  // Health NOT_SERVING while the unary budget is saturated (from a refusal
  // for want of room until half of it is free), so balancers send calls to
  // other replicas; SERVING again after.
  bool not_serving_when_saturated = true;
  // Connections (connection_limits.h). Concurrent calls on one connection
  // (HTTP/2 streams); a client needing more opens more connections.
  int max_calls_per_connection = 128;
  // The server pings a connection idle this long, and closes it when the ping
  // is not answered within keepalive_timeout_seconds (dead peers).
  double keepalive_seconds = 60;
  double keepalive_timeout_seconds = 20;
  // Clients may ping at most this often without data; more often, twice,
  // and the connection is closed (ENHANCE_YOUR_CALM).
  double min_client_ping_seconds = 10;
  // A connection with no call for this long is closed (GOAWAY); 0: never.
  double max_connection_idle_seconds = 900;
  // A connection older than this is asked to reconnect (GOAWAY), its calls
  // getting max_connection_age_grace_seconds to finish; 0: never. Set it
  // behind a balancer so that new replicas get their share of clients.
  double max_connection_age_seconds = 0;
  double max_connection_age_grace_seconds = 30;
  // After SIGTERM, drain_seconds + grace_seconds + this, scallopd exits 1
  // whatever is still running (work that cannot be cancelled).
  double hard_exit_seconds = 10;
  std::string default_world = "default";
  // Named worlds, sorted by name. "default" (seed 1, d 1, A3) is built in.
  std::map<std::string, World> worlds{{"default", *World::Create({.seed = 1})}};
  // Grayscale PNGs by name, loaded when the config is read (`rasters: {NAME:
  // PATH}`), for raster radius fields of named and inline worlds.
  RasterCatalog rasters;
};

// The largest area any method hands the engine: its own area limit, which
// each method applies to what it reads (Verify's halo, Follow's margin).
double LargestAreaLimit(const ServerConfig& config);

// Overrides `config` with the keys of a YAML file (the field names above, plus
// `rasters: {NAME: PATH}`, each a grayscale PNG read now, a relative PATH
// from the file's folder, and `worlds: {name: {seed, min_distance,
// algorithm, density, radius_field}}`, radius_field as the proto's World has
// it: `{noise: {r_min, r_max, frequency, octaves, gain, noise_seed}}` or
// `{raster: {raster_name, origin_x, origin_y, pixel_size, r_min, r_max}}`).
// INVALID_ARGUMENT naming the file and key on a bad value, an unknown key or
// a raster that cannot be read (missing, not a PNG, not grayscale, too large).
Status LoadConfigFile(const std::string& path, ServerConfig& config);

// Parses "NAME:SEED:MIN_DISTANCE:ALGORITHM[:DENSITY]" (the --world flag).
Status AddWorldSpec(const std::string& spec, ServerConfig& config);

// Checks ranges and that the default world exists; errors name the setting.
Status ValidateConfig(const ServerConfig& config);

}  // namespace scallop::server
