// scallopd's configuration: built-in defaults, then an optional YAML file,
// then command-line flags, each overriding the one before.
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "scallop/base/status.h"
#include "scallop/plane/world.h"

namespace scallop::server {

struct ServerConfig {
  std::string listen = "127.0.0.1:50051";  // HOST:PORT; port 0 picks a free one
  std::string metrics_listen;              // HOST:PORT of GET /metrics (Prometheus); empty: off
  int threads = 2;                         // request threads, and as many generating regions
  int64_t cache_megabytes = 512;           // region cache budget (about 32 bytes a point)
  int32_t max_page_size = 65536;           // points per GetPoints page (1.5 MB)
  double max_query_area = 1e6;             // GetPoints, in d^2 (about 850k points)
  double max_stream_area = 1e8;            // StreamPoints, in d^2
  double max_verify_area = 1e6;            // Verify, in d^2 (about 3.5 s on two cores)
  int max_in_flight = 64;                  // concurrent requests before RESOURCE_EXHAUSTED
  // 24 bytes in and 48 out a position: 2^16 positions is 3 MB of answer.
  int32_t max_nearest_batch = 1 << 16;       // positions per Nearest call
  int64_t max_noise_grid_samples = 1 << 19;  // width * height per NoiseGrid call (4 MB)
  double max_follow_area = 1e5;              // Follow viewport grown by keep_margin, in d^2
  double follow_stall_seconds = 10;          // a Follow client not reading is dropped after this
  double grace_seconds = 10;                 // in-flight requests get this long after SIGTERM
  double drain_seconds = 0;                  // NOT_SERVING this long before refusing new calls
  // debug, info (a line per call), warn (failed calls only), error or off.
  std::string log_level = "info";
  // Key for page tokens. Empty: derived from the world set (see page_token.h).
  std::string page_token_secret;
  std::string default_world = "default";
  // Named worlds, sorted by name. "default" (seed 1, d 1, A3) is built in.
  std::map<std::string, World> worlds{{"default", *World::Create({.seed = 1})}};
};

// The largest area any method hands the engine: its own area limit, which
// each method applies to what it reads (Verify's halo, Follow's margin).
double LargestAreaLimit(const ServerConfig& config);

// Overrides `config` with the keys of a YAML file (the field names above, plus
// `worlds: {name: {seed, min_distance, algorithm, density}}`). INVALID_ARGUMENT
// naming the file and key on a bad value or an unknown key.
Status LoadConfigFile(const std::string& path, ServerConfig& config);

// Parses "NAME:SEED:MIN_DISTANCE:ALGORITHM[:DENSITY]" (the --world flag).
Status AddWorldSpec(const std::string& spec, ServerConfig& config);

// Checks ranges and that the default world exists; errors name the setting.
Status ValidateConfig(const ServerConfig& config);

}  // namespace scallop::server
