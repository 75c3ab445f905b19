// load_generator: drives GetPoints on a scallopd (or on bench/null_server) from
// N concurrent client streams, one thread and one connection each, asking for
// square tiles cold (fresh places of a fresh world) or warm (a cached square),
// and reports requests/s, points/s, bytes/s and latency percentiles. Bounded
// in requests and in time; loopback targets only. See docs/performance.md.
//
//   load_generator --target 127.0.0.1:50051 --mode warm --streams 4 --duration 10
#include <grpcpp/grpcpp.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <iostream>
#include <random>
#include <thread>

#include "bench/load_report.h"
#include "bench/load_tile_plan.h"
#include "scallop_client.h"
#include "world_messages.h"

namespace scallop::load {
namespace {

using Clock = std::chrono::steady_clock;

struct LoadOptions {
  std::string target = "127.0.0.1:50051";
  std::string mode = "warm";
  int streams = 1;
  int64_t requests = 100000;
  double duration_seconds = 10;
  double tile_side = 64;
  double warm_side = 256;
  uint64_t run_seed = 0;  // 0: drawn from std::random_device, and printed
  int timeout_ms = 10000;
  std::string output = "text";
};

// Hard caps, so no command line can start an unbounded loop.
constexpr int64_t kMaxRequests = 10'000'000;
constexpr double kMaxDurationSeconds = 600;
constexpr int kMaxStreams = 256;

// The network rule of this project: only loopback targets.
bool IsLoopback(const std::string& target) {
  for (const char* prefix : {"127.", "localhost:", "[::1]:"}) {
    if (target.rfind(prefix, 0) == 0) return true;
  }
  return false;
}

// One connection per stream: a local subchannel pool stops gRPC from sharing
// one TCP connection among the channels, as separate clients would not.
std::shared_ptr<grpc::Channel> ConnectStream(const std::string& target) {
  grpc::ChannelArguments arguments;
  arguments.SetInt(GRPC_ARG_USE_LOCAL_SUBCHANNEL_POOL, 1);
  arguments.SetMaxReceiveMessageSize(64 << 20);
  return grpc::CreateCustomChannel(target, grpc::InsecureChannelCredentials(), arguments);
}

// Cold requests name a world inline with the run's seed: no earlier run (nor
// anything else on the server) can have cached a region of it. Warm requests
// use the server's default world.
v1::GetPointsRequest MakeRequest(const LoadOptions& options, const Rect& tile) {
  v1::GetPointsRequest request;
  if (options.mode == "cold") {
    v1::World& world = *request.mutable_world();
    world.set_seed(options.run_seed);
    world.set_min_distance(1);
    world.set_algorithm(v1::ALGORITHM_A3);
  }
  *request.mutable_rect() = RectToMessage(tile);
  return request;
}

// One call; on success, adds its latency, points and bytes to the tally.
void Call(client::ScallopClient& client, const v1::GetPointsRequest& request, int timeout_ms,
          StreamTally& tally) {
  v1::GetPointsResponse response;
  const Clock::time_point start = Clock::now();
  const grpc::Status status =
      client.GetPoints(request, response, {.timeout = std::chrono::milliseconds(timeout_ms)});
  const Clock::time_point end = Clock::now();
  if (!status.ok()) {
    ++tally.errors;
    if (tally.first_error.empty()) tally.first_error = client::DescribeStatus(status);
    return;
  }
  tally.latencies_ms.push_back(std::chrono::duration<double, std::milli>(end - start).count());
  tally.points += response.points().ids_size();
  tally.bytes += static_cast<int64_t>(response.ByteSizeLong());
}

// Connects every stream (not measured), so the first measured calls do not
// pay for TCP and HTTP/2 set-up. False if a stream cannot reach the server.
bool ConnectAll(std::vector<client::ScallopClient>& clients, int timeout_ms) {
  for (client::ScallopClient& client : clients) {
    const auto deadline = std::chrono::system_clock::now() + std::chrono::milliseconds(timeout_ms);
    if (!client.channel()->WaitForConnected(deadline)) return false;
  }
  return true;
}

int Run(const LoadOptions& options) {
  TilePlanOptions plan_options{.mode = options.mode == "cold" ? LoadMode::kCold : LoadMode::kWarm,
                               .tile_side = options.tile_side,
                               .warm_side = options.warm_side,
                               .run_seed = options.run_seed};
  const TilePlan plan(plan_options);
  std::vector<client::ScallopClient> clients;
  for (int s = 0; s < options.streams; ++s) clients.emplace_back(ConnectStream(options.target));
  if (!ConnectAll(clients, options.timeout_ms)) {
    std::cerr << "load_generator: cannot connect to " << options.target << '\n';
    return 1;
  }
  // Warm-up: every tile of the warm square once, spread over the streams'
  // connections; its errors fail the run, since the measure would be cold.
  const std::vector<Rect> warm_up = plan.WarmUpTiles();
  for (size_t k = 0; k < warm_up.size(); ++k) {
    StreamTally tally;
    Call(clients[k % clients.size()], MakeRequest(options, warm_up[k]), options.timeout_ms, tally);
    if (tally.errors > 0) {
      std::cerr << "load_generator: warm-up failed: " << tally.first_error << '\n';
      return 1;
    }
  }

  std::vector<StreamTally> tallies(static_cast<size_t>(options.streams));
  std::atomic<int64_t> next_request{0};
  const Clock::time_point start = Clock::now();
  const Clock::time_point stop =
      start + std::chrono::duration_cast<Clock::duration>(
                  std::chrono::duration<double>(options.duration_seconds));
  {
    std::vector<std::jthread> streams;
    for (int s = 0; s < options.streams; ++s) {
      streams.emplace_back([&, s] {
        StreamTally& tally = tallies[static_cast<size_t>(s)];
        tally.latencies_ms.reserve(4096);
        while (Clock::now() < stop) {
          const int64_t k = next_request.fetch_add(1, std::memory_order_relaxed);
          if (k >= options.requests) break;
          Call(clients[static_cast<size_t>(s)], MakeRequest(options, plan.Tile(k)),
               options.timeout_ms, tally);
        }
      });
    }
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();

  LoadSummary summary = Summarize(tallies, seconds);
  summary.target = options.target;
  summary.mode = options.mode;
  summary.streams = options.streams;
  summary.tile_side = options.tile_side;
  summary.run_seed = options.run_seed;
  if (options.output == "json") {
    PrintJson(summary, std::cout);
  } else if (options.output == "tsv") {
    PrintTsv(summary, std::cout);
  } else {
    PrintText(summary, std::cout);
  }
  return summary.errors == 0 ? 0 : 1;
}

}  // namespace
}  // namespace scallop::load

int main(int argc, char** argv) {
  using scallop::load::LoadOptions;
  LoadOptions options;
  CLI::App app{"load_generator: concurrent GetPoints load on scallopd or the null server"};
  app.add_option("--target", options.target, "HOST:PORT, loopback only")->capture_default_str();
  app.add_option("--mode", options.mode,
                 "cold: a fresh world, tiles 1024 d apart, nothing cached; "
                 "warm: tiles inside a square queried once before measuring")
      ->check(CLI::IsMember({"cold", "warm"}))
      ->capture_default_str();
  app.add_option("--streams", options.streams,
                 "Concurrent streams (a thread and a connection each)")
      ->check(CLI::Range(1, scallop::load::kMaxStreams))
      ->capture_default_str();
  app.add_option("--requests", options.requests, "Stop after this many requests")
      ->check(CLI::Range(int64_t{1}, scallop::load::kMaxRequests))
      ->capture_default_str();
  app.add_option("--duration", options.duration_seconds, "Stop after this many seconds")
      ->check(CLI::Range(0.1, scallop::load::kMaxDurationSeconds))
      ->capture_default_str();
  app.add_option("--tile", options.tile_side, "Tile side in d (the worlds have d = 1)")
      ->check(CLI::Range(1.0, 512.0))
      ->capture_default_str();
  app.add_option("--warm-side", options.warm_side, "Side of the warm square, in d")
      ->check(CLI::Range(1.0, 65536.0))
      ->capture_default_str();
  app.add_option("--seed", options.run_seed,
                 "Run seed: tile places, cold world (0: random, printed with the results)")
      ->capture_default_str();
  app.add_option("--timeout-ms", options.timeout_ms, "Deadline of each call")
      ->check(CLI::Range(1, 600000))
      ->capture_default_str();
  app.add_option("--output", options.output, "text, json or tsv (one row, see --tsv-header)")
      ->check(CLI::IsMember({"text", "json", "tsv"}))
      ->capture_default_str();
  bool tsv_header = false;
  app.add_flag("--tsv-header", tsv_header, "Print the TSV columns and exit");
  CLI11_PARSE(app, argc, argv);

  if (tsv_header) {
    std::cout << scallop::load::TsvHeader() << '\n';
    return 0;
  }
  if (!scallop::load::IsLoopback(options.target)) {
    std::cerr << "load_generator: --target must be a loopback address (127.x.x.x, localhost, "
                 "[::1]), got "
              << options.target << '\n';
    return 2;
  }
  if (options.mode == "cold" && options.requests > scallop::load::kMaxColdTiles) {
    options.requests = scallop::load::kMaxColdTiles;  // one lattice cell per request
  }
  if (options.mode == "warm" && options.warm_side < options.tile_side) {
    std::cerr << "load_generator: --warm-side must be at least --tile\n";
    return 2;
  }
  if (options.run_seed == 0) {
    std::random_device entropy;
    options.run_seed = (uint64_t{entropy()} << 32) | entropy();
    if (options.run_seed == 0) options.run_seed = 1;
  }
  return scallop::load::Run(options);
}
