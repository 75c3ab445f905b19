// scallopd: the Scallop gRPC server. Reads flags and an optional YAML config,
// serves scallop.v1.Scallop, grpc.health.v1 and reflection (over plaintext,
// TLS or mutual TLS; calls may need a token), and on SIGTERM or
// SIGINT goes NOT_SERVING, lets in-flight calls finish within the grace
// period, and exits 0.
#include <grpcpp/ext/proto_server_reflection_plugin.h>
#include <grpcpp/grpcpp.h>
#include <grpcpp/health_check_service_interface.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/thread_pool.hpp>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <set>
#include <thread>

#include "server/buffered_log_sink.h"
#include "server/connection_limits.h"
#include "server/http_api.h"
#include "server/lock_order_checks.h"
#include "server/malloc_tuning.h"
#include "server/metrics_http_server.h"
#include "server/page_token.h"
#include "server/request_metrics.h"
#include "server/scallop_service.h"
#include "server/server_config.h"
#include "server/serving_status.h"
#include "server/tls_credentials.h"
#include "server/token_table.h"
#include "server/world_registry.h"

namespace {

using scallop::server::ServerConfig;

// Linking grpc++_reflection registers its plugin from a static initializer,
// so not calling InitProtoReflectionServerBuilderPlugin leaves reflection on:
// --no-reflection takes the plugin out of the builder instead.
class WithoutReflection final : public grpc::ServerBuilderOption {
 public:
  void UpdateArguments(grpc::ChannelArguments*) override {}
  void UpdatePlugins(std::vector<std::unique_ptr<grpc::ServerBuilderPlugin>>* plugins) override {
    std::erase_if(*plugins, [](const std::unique_ptr<grpc::ServerBuilderPlugin>& plugin) {
      return dynamic_cast<grpc::reflection::ProtoServerReflectionPlugin*>(plugin.get()) != nullptr;
    });
  }
};

// Defaults, then the --config file, then the other flags. Exit code on error.
std::optional<int> ParseCommandLine(int argc, char** argv, ServerConfig& config) {
  CLI::App app{"scallopd: the Scallop gRPC server"};
  std::string config_path;
  std::vector<std::string> world_specs;
  ServerConfig flags;  // flag values, applied only when given
  app.add_option("--config", config_path, "YAML configuration file (flags override it)");
  app.add_option("--listen", flags.listen, "HOST:PORT to listen on (port 0: any free port)")
      ->default_str(config.listen);
  app.add_option("--metrics-listen", flags.metrics_listen,
                 "HOST:PORT serving Prometheus metrics at /metrics (port 0: any free port)");
  app.add_option("--http-listen", flags.http_listen,
                 "HOST:PORT serving HTTP tiles, /v1/worlds and the web viewer at / (port 0: any "
                 "free port)");
  app.add_option("--threads", flags.threads, "Request threads, and as many generating")
      ->default_str(std::to_string(config.threads));
  app.add_option("--cache-megabytes", flags.cache_megabytes, "Region cache budget")
      ->default_str(std::to_string(config.cache_megabytes));
  app.add_option("--max-page-size", flags.max_page_size, "Points per GetPoints page")
      ->default_str(std::to_string(config.max_page_size));
  app.add_option("--max-query-area", flags.max_query_area, "GetPoints area limit, d^2")
      ->default_str("1e6");
  app.add_option("--max-stream-area", flags.max_stream_area, "StreamPoints area limit, d^2")
      ->default_str("1e8");
  app.add_option("--max-verify-area", flags.max_verify_area, "Verify area limit, d^2")
      ->default_str("1e6");
  app.add_option("--max-in-flight", flags.max_in_flight, "Concurrent unary calls before shedding")
      ->default_str(std::to_string(config.max_in_flight));
  app.add_option("--max-streams-in-flight", flags.max_streams_in_flight,
                 "Concurrent streaming calls before shedding (apart from --max-in-flight)")
      ->default_str(std::to_string(config.max_streams_in_flight));
  app.add_flag("--reuse-port", flags.reuse_port,
               "Share the port with other processes (SO_REUSEPORT); without it a port in use "
               "is an error");
  app.add_option("--grace-seconds", flags.grace_seconds, "Time in-flight calls get on SIGTERM")
      ->default_str("10");
  app.add_option("--hard-exit-seconds", flags.hard_exit_seconds,
                 "After drain and grace, exit 1 this much later whatever still runs")
      ->default_str("10");
  app.add_option("--max-in-flight-cost", flags.max_in_flight_cost,
                 "Regions the unary calls in flight may touch in all")
      ->default_str(std::to_string(config.max_in_flight_cost));
  app.add_option("--max-client-share", flags.max_client_share,
                 "Share of the in-flight limits one client may hold")
      ->default_str("0.5");
  app.add_option("--rate-limit-per-second", flags.rate_limit_per_second,
                 "Calls a second per client (token, else IP address); 0: no limit")
      ->default_str("0");
  app.add_option("--rate-limit-burst", flags.rate_limit_burst, "Burst of --rate-limit-per-second")
      ->default_str("100");
  app.add_option("--max-connection-idle-seconds", flags.max_connection_idle_seconds,
                 "Close connections without a call this long (0: never)")
      ->default_str("900");
  app.add_option("--max-connection-age-seconds", flags.max_connection_age_seconds,
                 "Ask connections older than this to reconnect (0: never)")
      ->default_str("0");
  app.add_option("--max-calls-per-connection", flags.max_calls_per_connection,
                 "Concurrent calls on one connection")
      ->default_str(std::to_string(config.max_calls_per_connection));
  app.add_option("--drain-seconds", flags.drain_seconds,
                 "NOT_SERVING this long on SIGTERM before new calls are refused")
      ->default_str("0");
  // From the environment too, so the key can come from a secret store
  // (Kubernetes secretKeyRef) rather than a command line anyone can read.
  app.add_option("--page-token-secret", flags.page_token_secret,
                 "Key of page tokens (default: derived from the world set)")
      ->envname("SCALLOPD_PAGE_TOKEN_SECRET");
  app.add_option("--log-level", flags.log_level,
                 "debug, info (a line per call), warn (failed calls only), error or off")
      ->default_str(config.log_level);
  app.add_option("--default-world", flags.default_world, "World used when a request names none")
      ->default_str(config.default_world);
  app.add_option("--tls-cert", flags.tls_cert, "PEM certificate chain of the server (TLS)");
  app.add_option("--tls-key", flags.tls_key, "PEM private key of --tls-cert");
  app.add_option("--tls-client-ca", flags.tls_client_ca,
                 "PEM CA that must sign client certificates (mutual TLS)");
  app.add_option("--auth-tokens", flags.auth_tokens,
                 "File of bearer tokens, 'TOKEN [WORLD,...]' a line; calls need one");
  bool no_reflection = false;
  app.add_flag("--no-reflection", no_reflection, "Do not serve gRPC reflection");
  app.add_option("--world", world_specs, "Named world NAME:SEED:MIN_DISTANCE:ALGORITHM[:DENSITY]");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  if (!config_path.empty()) {
    if (scallop::Status status = scallop::server::LoadConfigFile(config_path, config);
        !status.ok()) {
      std::cerr << "scallopd: " << status.message() << '\n';
      return 2;
    }
  }
  auto apply = [&](const char* flag, auto member) {
    if (app.count(flag) > 0) config.*member = flags.*member;
  };
  apply("--listen", &ServerConfig::listen);
  apply("--metrics-listen", &ServerConfig::metrics_listen);
  apply("--http-listen", &ServerConfig::http_listen);
  apply("--threads", &ServerConfig::threads);
  apply("--cache-megabytes", &ServerConfig::cache_megabytes);
  apply("--max-page-size", &ServerConfig::max_page_size);
  apply("--max-query-area", &ServerConfig::max_query_area);
  apply("--max-stream-area", &ServerConfig::max_stream_area);
  apply("--max-verify-area", &ServerConfig::max_verify_area);
  apply("--max-in-flight", &ServerConfig::max_in_flight);
  apply("--max-streams-in-flight", &ServerConfig::max_streams_in_flight);
  apply("--reuse-port", &ServerConfig::reuse_port);
  apply("--grace-seconds", &ServerConfig::grace_seconds);
  apply("--drain-seconds", &ServerConfig::drain_seconds);
  apply("--hard-exit-seconds", &ServerConfig::hard_exit_seconds);
  apply("--max-in-flight-cost", &ServerConfig::max_in_flight_cost);
  apply("--max-client-share", &ServerConfig::max_client_share);
  apply("--rate-limit-per-second", &ServerConfig::rate_limit_per_second);
  apply("--rate-limit-burst", &ServerConfig::rate_limit_burst);
  apply("--max-connection-idle-seconds", &ServerConfig::max_connection_idle_seconds);
  apply("--max-connection-age-seconds", &ServerConfig::max_connection_age_seconds);
  apply("--max-calls-per-connection", &ServerConfig::max_calls_per_connection);
  apply("--page-token-secret", &ServerConfig::page_token_secret);
  apply("--default-world", &ServerConfig::default_world);
  apply("--log-level", &ServerConfig::log_level);
  apply("--tls-cert", &ServerConfig::tls_cert);
  apply("--tls-key", &ServerConfig::tls_key);
  apply("--tls-client-ca", &ServerConfig::tls_client_ca);
  apply("--auth-tokens", &ServerConfig::auth_tokens);
  if (no_reflection) config.reflection = false;
  for (const std::string& spec : world_specs) {
    if (scallop::Status status = scallop::server::AddWorldSpec(spec, config); !status.ok()) {
      std::cerr << "scallopd: " << status.message() << '\n';
      return 2;
    }
  }
  if (scallop::Status status = scallop::server::ValidateConfig(config); !status.ok()) {
    std::cerr << "scallopd: " << status.message() << '\n';
    return 2;
  }
  return std::nullopt;
}

}  // namespace

int main(int argc, char** argv) {
  ServerConfig config;
  if (std::optional<int> exit_code = ParseCommandLine(argc, argv, config)) return *exit_code;
  // Before anything binds a port: a bad TLS file stops scallopd with its name.
  scallop::StatusOr<std::shared_ptr<grpc::ServerCredentials>> credentials =
      scallop::server::MakeServerCredentials(config);
  if (!credentials.ok()) {
    std::cerr << "scallopd: " << credentials.status().message() << '\n';
    return 2;
  }
  // Before any listener is announced: the signal set's descriptors must not
  // be the ones a client flood leaves the process without (EMFILE once made
  // this constructor throw after the metrics port was printed).
  boost::asio::io_context signals_context;
  boost::asio::signal_set signals(signals_context, SIGINT, SIGTERM);
  scallop::server::TuneMallocForResponses();
  scallop::server::TurnOffLockOrderChecks();
  // Logs on stderr; stdout carries only the address line, for scripts and tests.
  // Call lines are written in batches (buffered_log_sink.h): within a second,
  // and warnings and errors at once.
  spdlog::set_default_logger(std::make_shared<spdlog::logger>(
      "scallopd", std::make_shared<scallop::server::BufferedLogSink>(STDERR_FILENO)));
  spdlog::set_level(
      spdlog::level::from_str(config.log_level));  // validated: never "off" by mistake
  spdlog::flush_on(spdlog::level::warn);
  spdlog::flush_every(std::chrono::seconds(1));

  const scallop::server::WorldRegistry worlds(config.worlds, config.default_world, config.rasters);
  std::optional<scallop::server::TokenTable> tokens;
  if (!config.auth_tokens.empty()) {
    const std::vector<std::string> names = worlds.names();
    auto loaded = scallop::server::TokenTable::Load(
        config.auth_tokens, std::set<std::string>(names.begin(), names.end()));
    if (!loaded.ok()) {
      std::cerr << "scallopd: " << loaded.status().message() << '\n';
      return 2;
    }
    tokens = std::move(*loaded);
  }
  const scallop::server::PageTokenCodec page_tokens(
      config.page_token_secret.empty() ? "scallop-page-token/" + worlds.Fingerprint()
                                       : config.page_token_secret);
  // Each method checks its own limit (query_rect.h) on what it reads before
  // calling the engine, so the engine's own check, the largest of them, never
  // refuses what a method let through.
  scallop::PlaneEngine engine({.cache_bytes = config.cache_megabytes << 20,
                               .threads = config.threads,
                               .max_query_area = scallop::server::LargestAreaLimit(config)});
  boost::asio::thread_pool request_pool(static_cast<size_t>(config.threads));
  scallop::server::RequestMetrics metrics;
  scallop::server::ScallopService service(config, worlds, page_tokens, engine, request_pool,
                                          &metrics, tokens ? &*tokens : nullptr);

  // Bound before the gRPC port, so a bad --metrics-listen fails before the
  // server announces itself; announced after, so the address line stays first.
  std::unique_ptr<scallop::server::MetricsHttpServer> metrics_server;
  if (!config.metrics_listen.empty()) {
    auto started = scallop::server::MetricsHttpServer::Start(
        config.metrics_listen,
        [&] { return metrics.Exposition(engine.CacheStats(), service.requests_in_flight()); },
        config.max_metrics_connections);
    if (!started.ok()) {
      std::cerr << "scallopd: " << started.status().message() << '\n';
      return 2;
    }
    metrics_server = std::move(*started);
  }
  // The same: bound before, announced after the gRPC port.
  scallop::server::HttpApi http_api(service.context());
  std::unique_ptr<scallop::server::HttpListener> http_listener;
  if (!config.http_listen.empty()) {
    auto started = scallop::server::HttpListener::Start(
        config.http_listen, "http",
        [&http_api](const scallop::server::HttpListener::Request& request, const std::string& peer,
                    const scallop::server::HttpListener::Respond& respond) {
          http_api.Handle(request, peer, respond);
        },
        config.max_http_connections, config.threads);
    if (!started.ok()) {
      std::cerr << "scallopd: " << started.status().message() << '\n';
      return 2;
    }
    http_listener = std::move(*started);
  }

  grpc::EnableDefaultHealthCheckService(true);
  grpc::reflection::InitProtoReflectionServerBuilderPlugin();
  grpc::ServerBuilder builder;
  int port = 0;
  // gRPC shares ports by default (SO_REUSEPORT): a second scallopd on a port
  // in use would start silently and take half the calls. Only on request.
  builder.AddChannelArgument(GRPC_ARG_ALLOW_REUSEPORT, config.reuse_port ? 1 : 0);
  scallop::server::ApplyConnectionLimits(config, builder);
  builder.AddListeningPort(config.listen, *credentials, &port);
  builder.RegisterService(&service);
  if (!config.reflection) builder.SetOption(std::make_unique<WithoutReflection>());
  std::unique_ptr<grpc::Server> server = builder.BuildAndStart();
  if (!server || port == 0) {
    spdlog::error("cannot listen on {} (in use? --reuse-port shares a port on purpose)",
                  config.listen);
    return 1;
  }
  scallop::server::ServingStatus serving(server->GetHealthCheckService());
  if (config.not_serving_when_saturated) {
    service.OnSaturationChange([&serving](bool saturated) { serving.SetSaturated(saturated); });
  }
  const std::string host = config.listen.substr(0, config.listen.rfind(':'));
  std::cout << "scallopd listening on " << host << ':' << port << std::endl;
  if (metrics_server) {
    const std::string metrics_host =
        config.metrics_listen.substr(0, config.metrics_listen.rfind(':'));
    std::cout << "scallopd metrics on " << metrics_host << ':' << metrics_server->port()
              << std::endl;
  }
  if (http_listener) {
    const std::string http_host = config.http_listen.substr(0, config.http_listen.rfind(':'));
    std::cout << "scallopd http on " << http_host << ':' << http_listener->port() << std::endl;
  }
  if (tokens && config.tls_cert.empty()) {
    spdlog::warn(
        "bearer tokens over plaintext can be read on the way: set tls_cert and tls_key, or "
        "keep scallopd behind a proxy that terminates TLS");
  }
  if (config.page_token_secret.empty()) {
    spdlog::warn(
        "page tokens are keyed from the world set, which anyone who knows the worlds can "
        "compute; set page_token_secret (or SCALLOPD_PAGE_TOKEN_SECRET) in production");
  }
  spdlog::info(
      "listening on {}:{}; default world {} ({}); {} threads; {}; {}", host, port,
      config.default_world, config.worlds.at(config.default_world).Describe(), config.threads,
      config.tls_client_ca.empty() ? (config.tls_cert.empty() ? "plaintext" : "TLS") : "mutual TLS",
      tokens ? std::to_string(tokens->size()) + " tokens" : "no token needed");

  signals.async_wait([&](const boost::system::error_code& error, int signal_number) {
    if (error) return;
    spdlog::info("signal {}: NOT_SERVING, draining {} s, then {} s of grace for in-flight calls",
                 signal_number, config.drain_seconds, config.grace_seconds);
    serving.SetDraining();
    // Work that cannot be cancelled (a CGAL triangulation, say) must not keep
    // the process past every deadline: exit 1 then, whatever still runs.
    std::thread([&config] {
      std::this_thread::sleep_for(std::chrono::duration<double>(
          config.drain_seconds + config.grace_seconds + config.hard_exit_seconds));
      spdlog::error(
          "hard exit: calls still running {} s after the grace period (hard_exit_seconds)",
          config.hard_exit_seconds);
      spdlog::default_logger()->flush();
      std::_Exit(1);
    }).detach();
    std::this_thread::sleep_for(std::chrono::duration<double>(config.drain_seconds));
    // Refuses new calls at once; calls still running at the deadline are cancelled.
    const auto deadline = std::chrono::system_clock::now() +
                          std::chrono::duration_cast<std::chrono::system_clock::duration>(
                              std::chrono::duration<double>(config.grace_seconds));
    server->Shutdown(deadline);
  });
  signals_context.run();
  server->Wait();
  // Tiles still on the pool finish before the listener that answers them stops.
  request_pool.join();
  if (http_listener) http_listener->Stop();
  if (metrics_server) metrics_server->Stop();
  spdlog::info("stopped");
  spdlog::shutdown();  // the held lines written, the flushing thread stopped
  return 0;
}
