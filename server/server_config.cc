// Loading and checking scallopd's configuration (YAML file and --world specs).
#include "server/server_config.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <optional>
#include <set>
#include <sstream>
#include <tuple>
#include <vector>

#include "field_messages.h"
#include "world_yaml.h"

namespace scallop::server {
namespace {

StatusOr<World> WorldFromFields(const std::string& where, uint64_t seed, double min_distance,
                                const std::string& algorithm_name, double density,
                                std::optional<RadiusFieldSpec> field = std::nullopt) {
  StatusOr<WorldAlgorithm> algorithm = ParseWorldAlgorithm(algorithm_name, where + ".algorithm");
  if (!algorithm.ok()) return algorithm.status();
  StatusOr<World> world = World::Create({.seed = seed,
                                         .min_distance = min_distance,
                                         .algorithm = *algorithm,
                                         .density = density,
                                         .radius_field = std::move(field)});
  if (!world.ok()) return InvalidArgument(where + ": " + world.status().message());
  return world;
}

// The settings of limits per client and per connection.
Status ValidateClientLimits(const ServerConfig& config) {
  if (config.max_in_flight_cost < 1) return InvalidArgument("max_in_flight_cost: must be >= 1");
  if (!(config.max_client_share > 0 && config.max_client_share <= 1)) {
    return InvalidArgument("max_client_share: must be in (0, 1]");
  }
  if (!(config.rate_limit_per_second >= 0 && config.rate_limit_per_second <= 1e9)) {
    return InvalidArgument("rate_limit_per_second: must be in [0, 1e9] (0: no limit)");
  }
  if (!(config.rate_limit_burst >= 1 && config.rate_limit_burst <= 1e9)) {
    return InvalidArgument("rate_limit_burst: must be in [1, 1e9]");
  }
  if (config.max_calls_per_connection < 1 || config.max_calls_per_connection > 65536) {
    return InvalidArgument("max_calls_per_connection: must be in 1..65536");
  }
  // Milliseconds in an int for gRPC: up to about 24 days.
  for (const auto& [name, value, zero_allowed] :
       {std::tuple{"keepalive_seconds", config.keepalive_seconds, false},
        {"keepalive_timeout_seconds", config.keepalive_timeout_seconds, false},
        {"min_client_ping_seconds", config.min_client_ping_seconds, false},
        {"max_connection_idle_seconds", config.max_connection_idle_seconds, true},
        {"max_connection_age_seconds", config.max_connection_age_seconds, true},
        {"max_connection_age_grace_seconds", config.max_connection_age_grace_seconds, true},
        {"hard_exit_seconds", config.hard_exit_seconds, true}}) {
    if (!((zero_allowed ? value >= 0 : value > 0) && value <= 2e6)) {
      return InvalidArgument(std::string(name) + ": must be in " + (zero_allowed ? "[0" : "(0") +
                             ", 2e6] seconds");
    }
  }
  return Status::Ok();
}

}  // namespace

Status LoadConfigFile(const std::string& path, ServerConfig& config) {
  const std::set<std::string> known{"listen",
                                    "threads",
                                    "cache_megabytes",
                                    "max_page_size",
                                    "max_query_area",
                                    "max_stream_area",
                                    "max_verify_area",
                                    "max_in_flight",
                                    "grace_seconds",
                                    "drain_seconds",
                                    "page_token_secret",
                                    "default_world",
                                    "worlds",
                                    "rasters",
                                    "max_nearest_batch",
                                    "max_noise_grid_samples",
                                    "max_follow_area",
                                    "follow_stall_seconds",
                                    "follow_idle_seconds",
                                    "stream_stall_seconds",
                                    "max_streams_in_flight",
                                    "max_nearest_regions",
                                    "max_metrics_connections",
                                    "reuse_port",
                                    "metrics_listen",
                                    "http_listen",
                                    "max_http_connections",
                                    "http_max_age_seconds",
                                    "log_level",
                                    "tls_cert",
                                    "tls_key",
                                    "tls_client_ca",
                                    "auth_tokens",
                                    "reflection",
                                    "max_in_flight_cost",
                                    "max_client_share",
                                    "rate_limit_per_second",
                                    "rate_limit_burst",
                                    "not_serving_when_saturated",
                                    "max_calls_per_connection",
                                    "keepalive_seconds",
                                    "keepalive_timeout_seconds",
                                    "min_client_ping_seconds",
                                    "max_connection_idle_seconds",
                                    "max_connection_age_seconds",
                                    "max_connection_age_grace_seconds",
                                    "hard_exit_seconds"};
  std::string key;
  try {
    const YAML::Node root = YAML::LoadFile(path);
    if (!root.IsMap()) return InvalidArgument(path + ": must be a map of settings");
    for (const auto& entry : root) {
      key = entry.first.as<std::string>();
      if (!known.contains(key)) return InvalidArgument(path + ": unknown setting '" + key + "'");
    }
    auto read = [&](const char* name, auto& value) {
      key = name;
      if (root[name]) value = root[name].as<std::decay_t<decltype(value)>>();
    };
    read("listen", config.listen);
    read("metrics_listen", config.metrics_listen);
    read("http_listen", config.http_listen);
    read("max_http_connections", config.max_http_connections);
    read("http_max_age_seconds", config.http_max_age_seconds);
    read("threads", config.threads);
    read("cache_megabytes", config.cache_megabytes);
    read("max_page_size", config.max_page_size);
    read("max_query_area", config.max_query_area);
    read("max_stream_area", config.max_stream_area);
    read("max_verify_area", config.max_verify_area);
    read("max_in_flight", config.max_in_flight);
    read("max_nearest_batch", config.max_nearest_batch);
    read("max_noise_grid_samples", config.max_noise_grid_samples);
    read("max_follow_area", config.max_follow_area);
    read("follow_stall_seconds", config.follow_stall_seconds);
    read("follow_idle_seconds", config.follow_idle_seconds);
    read("stream_stall_seconds", config.stream_stall_seconds);
    read("max_streams_in_flight", config.max_streams_in_flight);
    read("max_nearest_regions", config.max_nearest_regions);
    read("max_metrics_connections", config.max_metrics_connections);
    read("reuse_port", config.reuse_port);
    read("grace_seconds", config.grace_seconds);
    read("drain_seconds", config.drain_seconds);
    read("log_level", config.log_level);
    read("page_token_secret", config.page_token_secret);
    read("default_world", config.default_world);
    read("tls_cert", config.tls_cert);
    read("tls_key", config.tls_key);
    read("tls_client_ca", config.tls_client_ca);
    read("auth_tokens", config.auth_tokens);
    read("reflection", config.reflection);
    read("max_in_flight_cost", config.max_in_flight_cost);
    read("max_client_share", config.max_client_share);
    read("rate_limit_per_second", config.rate_limit_per_second);
    read("rate_limit_burst", config.rate_limit_burst);
    read("not_serving_when_saturated", config.not_serving_when_saturated);
    read("max_calls_per_connection", config.max_calls_per_connection);
    read("keepalive_seconds", config.keepalive_seconds);
    read("keepalive_timeout_seconds", config.keepalive_timeout_seconds);
    read("min_client_ping_seconds", config.min_client_ping_seconds);
    read("max_connection_idle_seconds", config.max_connection_idle_seconds);
    read("max_connection_age_seconds", config.max_connection_age_seconds);
    read("max_connection_age_grace_seconds", config.max_connection_age_grace_seconds);
    read("hard_exit_seconds", config.hard_exit_seconds);
    // Rasters first: worlds name them. A relative path is read from the config's folder, so
    // a config and its images move together.
    for (const auto& entry : root["rasters"]) {
      const std::string name = entry.first.as<std::string>();
      key = "rasters." + name;
      std::filesystem::path file = entry.second.as<std::string>();
      if (file.is_relative()) file = std::filesystem::path(path).parent_path() / file;
      if (Status loaded = config.rasters.Load(name, file.string(), path + ": " + key);
          !loaded.ok()) {
        return loaded;
      }
    }
    for (const auto& entry : root["worlds"]) {
      const std::string name = entry.first.as<std::string>();
      const YAML::Node& fields = entry.second;
      key = "worlds." + name;
      StatusOr<World> world = WorldFromYaml(fields, config.rasters, path + ": " + key);
      if (!world.ok()) return world.status();
      config.worlds[name] = *world;
    }
  } catch (const YAML::Exception& e) {
    return InvalidArgument(path + ": " + (key.empty() ? "" : key + ": ") + e.what());
  }
  return Status::Ok();
}

Status AddWorldSpec(const std::string& spec, ServerConfig& config) {
  std::vector<std::string> parts;
  std::stringstream stream(spec);
  for (std::string part; std::getline(stream, part, ':');) parts.push_back(part);
  const std::string usage =
      "--world: expected NAME:SEED:MIN_DISTANCE:ALGORITHM[:DENSITY], got '" + spec + "'";
  if (parts.size() < 4 || parts.size() > 5 || parts[0].empty()) return InvalidArgument(usage);
  uint64_t seed = 0;
  const auto [end, error] =
      std::from_chars(parts[1].data(), parts[1].data() + parts[1].size(), seed);
  if (error != std::errc() || end != parts[1].data() + parts[1].size()) {
    return InvalidArgument(usage + " (seed must be in 0..2^64-1)");
  }
  try {
    const double min_distance = std::stod(parts[2]);
    const double density = parts.size() == 5 ? std::stod(parts[4]) : 2.0;
    StatusOr<World> world =
        WorldFromFields("--world " + parts[0], seed, min_distance, parts[3], density);
    if (!world.ok()) return world.status();
    config.worlds[parts[0]] = *world;
  } catch (const std::exception&) {
    return InvalidArgument(usage + " (min_distance and density must be numbers)");
  }
  return Status::Ok();
}

double LargestAreaLimit(const ServerConfig& config) {
  return std::max({config.max_query_area, config.max_stream_area, config.max_verify_area,
                   config.max_follow_area});
}

Status ValidateConfig(const ServerConfig& config) {
  if (config.threads < 1 || config.threads > 256) {
    return InvalidArgument("threads: must be in 1..256");
  }
  if (config.cache_megabytes < 0) return InvalidArgument("cache_megabytes: must be >= 0");
  // 24 bytes a point: 2^17 points is 3 MB, under gRPC's default 4 MB receive
  // limit, so a full page reaches clients that never raised theirs.
  if (config.max_page_size < 1 || config.max_page_size > (1 << 17)) {
    return InvalidArgument("max_page_size: must be in 1..131072");
  }
  for (const auto& [name, value] : {std::pair{"max_query_area", config.max_query_area},
                                    {"max_stream_area", config.max_stream_area},
                                    {"max_verify_area", config.max_verify_area},
                                    {"max_follow_area", config.max_follow_area}}) {
    if (!(value > 0 && value <= 1e12)) {
      return InvalidArgument(std::string(name) + ": must be in (0, 1e12] (units of d^2)");
    }
  }
  if (config.max_in_flight < 1) return InvalidArgument("max_in_flight: must be >= 1");
  if (config.max_streams_in_flight < 1) {
    return InvalidArgument("max_streams_in_flight: must be >= 1");
  }
  if (config.max_metrics_connections < 1 || config.max_metrics_connections > 1024) {
    return InvalidArgument("max_metrics_connections: must be in 1..1024");
  }
  if (config.max_http_connections < 1 || config.max_http_connections > 65536) {
    return InvalidArgument("max_http_connections: must be in 1..65536");
  }
  if (config.http_max_age_seconds < 0 || config.http_max_age_seconds > 31536000) {
    return InvalidArgument("http_max_age_seconds: must be in 0..31536000 (a year)");
  }
  // The same 3 MB bound as pages: answers fit gRPC's default receive limit.
  if (config.max_nearest_batch < 1 || config.max_nearest_batch > (1 << 16)) {
    return InvalidArgument("max_nearest_batch: must be in 1..65536");
  }
  // 8 bytes a sample: 2^19 samples was 37 bytes over 4 MiB with the envelope.
  if (config.max_noise_grid_samples < 1 || config.max_noise_grid_samples > 500000) {
    return InvalidArgument("max_noise_grid_samples: must be in 1..500000");
  }
  // 2^20 regions of cold grids is about 12 GB of them: far past any budget.
  if (config.max_nearest_regions < 1 || config.max_nearest_regions > (1 << 20)) {
    return InvalidArgument("max_nearest_regions: must be in 1..1048576");
  }
  for (const auto& [name, value] : {std::pair{"follow_stall_seconds", config.follow_stall_seconds},
                                    {"follow_idle_seconds", config.follow_idle_seconds},
                                    {"stream_stall_seconds", config.stream_stall_seconds}}) {
    if (!(value > 0 && value <= 3600)) {
      return InvalidArgument(std::string(name) + ": must be in (0, 3600]");
    }
  }
  if (!(config.grace_seconds >= 0 && config.grace_seconds <= 3600)) {
    return InvalidArgument("grace_seconds: must be in [0, 3600]");
  }
  if (!(config.drain_seconds >= 0 && config.drain_seconds <= 3600)) {
    return InvalidArgument("drain_seconds: must be in [0, 3600]");
  }
  if (!std::set<std::string>{"debug", "info", "warn", "error", "off"}.contains(config.log_level)) {
    return InvalidArgument("log_level: must be debug, info, warn, error or off, got '" +
                           config.log_level + "'");
  }
  // Files are read (and their errors named) when the server starts; here only
  // the combinations, so a half-configured TLS never falls back to plaintext.
  if (config.tls_cert.empty() != config.tls_key.empty()) {
    return InvalidArgument("tls_cert and tls_key: give both (TLS) or neither (plaintext)");
  }
  if (!config.tls_client_ca.empty() && config.tls_cert.empty()) {
    return InvalidArgument("tls_client_ca: needs tls_cert and tls_key (mutual TLS is TLS)");
  }
  if (Status status = ValidateClientLimits(config); !status.ok()) return status;
  if (!config.worlds.contains(config.default_world)) {
    return InvalidArgument("default_world: no world named '" + config.default_world + "'");
  }
  return Status::Ok();
}

}  // namespace scallop::server
