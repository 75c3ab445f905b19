// load_generator: drives GetPoints on a scallopd (or on bench/null_server) from
// N concurrent client streams, one thread and one connection each, asking for
// square tiles cold (fresh places of a fresh world) or warm (a cached square),
// and reports requests/s, points/s, bytes/s and latency percentiles. Bounded
// in requests and in time; loopback targets only. See docs/performance.md.
//
// Given several targets, it drives them in turns of --slice seconds, in the
// order given and then reversed (A B B A A B ...), each target --duration
// seconds in all, and reports each apart: a change of the machine's load
// slower than a slice then reaches every target alike, so their ratio is
// one measured under the same load. In warm mode a turn starts with one
// call a stream that is not counted (RunTurn says why).
//
//   load_generator --target 127.0.0.1:50051 --mode warm --streams 4 --duration 10
//   load_generator --target 127.0.0.1:50051 --target 127.0.0.1:50052 --slice 1 --duration 10
#include <grpcpp/grpcpp.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "bench/load_report.h"
#include "bench/load_tile_plan.h"
#include "bench/loopback_target.h"
#include "scallop_client.h"
#include "world_messages.h"

namespace scallop::load {
namespace {

using Clock = std::chrono::steady_clock;

struct LoadOptions {
  std::vector<std::string> targets = {"127.0.0.1:50051"};
  std::string mode = "warm";
  int streams = 1;
  int64_t requests = 100000;
  double duration_seconds = 10;  // each target's, in all
  double slice_seconds = 1;      // a turn, with several targets
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
constexpr int kMaxTargets = 8;

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

// A target's connections and what its calls measured.
struct TargetLoad {
  std::string address;
  std::vector<client::ScallopClient> clients;  // one a stream
  std::vector<StreamTally> tallies;            // one a stream
  std::atomic<int64_t> next_request{0};        // of the plan's tiles, its own
  double seconds = 0;                          // measured, over its turns
};

// Connects every stream and asks every tile of the warm square once, spread
// over the connections (not measured): the first measured calls pay neither
// for TCP and HTTP/2 set-up nor for a cold cache. False, said on stderr, if
// the target cannot be reached or a warm-up call fails.
bool Prepare(const LoadOptions& options, const TilePlan& plan, TargetLoad& target) {
  for (int s = 0; s < options.streams; ++s)
    target.clients.emplace_back(ConnectStream(target.address));
  if (!ConnectAll(target.clients, options.timeout_ms)) {
    std::cerr << "load_generator: cannot connect to " << target.address << '\n';
    return false;
  }
  const std::vector<Rect> warm_up = plan.WarmUpTiles();
  for (size_t k = 0; k < warm_up.size(); ++k) {
    StreamTally tally;
    Call(target.clients[k % target.clients.size()], MakeRequest(options, warm_up[k]),
         options.timeout_ms, tally);
    if (tally.errors > 0) {
      std::cerr << "load_generator: warm-up of " << target.address
                << " failed: " << tally.first_error << '\n';
      return false;
    }
  }
  target.tallies.resize(static_cast<size_t>(options.streams));
  for (StreamTally& tally : target.tallies) tally.latencies_ms.reserve(4096);
  return true;
}

// One turn: every stream calls `target` until `seconds` have passed (a call
// started before then is finished and counted) or its requests are spent.
// With `wake_first`, each stream first makes one call that is neither timed
// nor counted (a warm tile: it changes no cache): a gRPC server idle for a
// second (during the other targets' turns) lets its callback threads sleep
// 100 ms between polls (gRPC's CallbackAlternativeCQ), and the first call of
// a turn would wait that out, whichever server it is.
void RunTurn(const LoadOptions& options, const TilePlan& plan, TargetLoad& target, double seconds,
             bool wake_first) {
  if (wake_first) {
    std::vector<std::jthread> streams;
    for (int s = 0; s < options.streams; ++s) {
      streams.emplace_back([&, s] {
        StreamTally ignored;
        Call(target.clients[static_cast<size_t>(s)], MakeRequest(options, plan.Tile(s)),
             options.timeout_ms, ignored);
      });
    }
  }
  const Clock::time_point start = Clock::now();
  const Clock::time_point stop =
      start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  {
    std::vector<std::jthread> streams;
    for (int s = 0; s < options.streams; ++s) {
      streams.emplace_back([&, s] {
        StreamTally& tally = target.tallies[static_cast<size_t>(s)];
        while (Clock::now() < stop) {
          const int64_t k = target.next_request.fetch_add(1, std::memory_order_relaxed);
          if (k >= options.requests) break;
          Call(target.clients[static_cast<size_t>(s)], MakeRequest(options, plan.Tile(k)),
               options.timeout_ms, tally);
        }
      });
    }
  }
  target.seconds += std::chrono::duration<double>(Clock::now() - start).count();
}

int Run(const LoadOptions& options) {
  TilePlanOptions plan_options{.mode = options.mode == "cold" ? LoadMode::kCold : LoadMode::kWarm,
                               .tile_side = options.tile_side,
                               .warm_side = options.warm_side,
                               .run_seed = options.run_seed};
  const TilePlan plan(plan_options);
  std::vector<std::unique_ptr<TargetLoad>> targets;
  for (const std::string& address : options.targets) {
    targets.push_back(std::make_unique<TargetLoad>());
    targets.back()->address = address;
    if (!Prepare(options, plan, *targets.back())) return 1;
  }
  // One target: one turn of --duration. Several: turns of about --slice, as
  // many for each, in the order given and then reversed, so that a load
  // rising or falling steadily over two cycles weighs the same on each.
  const int turns =
      targets.size() == 1
          ? 1
          : std::max(
                1, static_cast<int>(std::lround(options.duration_seconds / options.slice_seconds)));
  const double turn_seconds = options.duration_seconds / turns;
  for (int cycle = 0; cycle < turns; ++cycle) {
    for (size_t n = 0; n < targets.size(); ++n) {
      const size_t t = cycle % 2 == 0 ? n : targets.size() - 1 - n;
      RunTurn(options, plan, *targets[t], turn_seconds,
              /*wake_first=*/targets.size() > 1 && options.mode == "warm");
    }
  }

  int64_t errors = 0;
  if (options.output == "json" && targets.size() > 1) std::cout << "[\n";
  for (size_t t = 0; t < targets.size(); ++t) {
    LoadSummary summary = Summarize(targets[t]->tallies, targets[t]->seconds);
    summary.target = targets[t]->address;
    summary.mode = options.mode;
    summary.streams = options.streams;
    summary.tile_side = options.tile_side;
    summary.run_seed = options.run_seed;
    errors += summary.errors;
    if (options.output == "json") {
      if (t > 0) std::cout << ",\n";
      PrintJson(summary, std::cout);
    } else if (options.output == "tsv") {
      PrintTsv(summary, std::cout);
    } else {
      PrintText(summary, std::cout);
    }
  }
  if (options.output == "json" && targets.size() > 1) std::cout << "]\n";
  return errors == 0 ? 0 : 1;
}

}  // namespace
}  // namespace scallop::load

int main(int argc, char** argv) {
  using scallop::load::LoadOptions;
  LoadOptions options;
  CLI::App app{"load_generator: concurrent GetPoints load on scallopd or the null server"};
  app.add_option("--target", options.targets,
                 "HOST:PORT, loopback only; repeat it to drive several in turns (--slice)")
      ->capture_default_str();
  app.add_option("--mode", options.mode,
                 "cold: a fresh world, tiles 1024 d apart, nothing cached; "
                 "warm: tiles inside a square queried once before measuring")
      ->check(CLI::IsMember({"cold", "warm"}))
      ->capture_default_str();
  app.add_option("--streams", options.streams,
                 "Concurrent streams (a thread and a connection each)")
      ->check(CLI::Range(1, scallop::load::kMaxStreams))
      ->capture_default_str();
  app.add_option("--requests", options.requests, "Stop after this many requests (each target's)")
      ->check(CLI::Range(int64_t{1}, scallop::load::kMaxRequests))
      ->capture_default_str();
  app.add_option("--duration", options.duration_seconds,
                 "Stop after this many seconds (each target's, over its turns)")
      ->check(CLI::Range(0.1, scallop::load::kMaxDurationSeconds))
      ->capture_default_str();
  app.add_option("--slice", options.slice_seconds,
                 "With several targets, the seconds of a turn: targets alternate A B B A ...")
      ->check(CLI::Range(0.05, scallop::load::kMaxDurationSeconds))
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
  if (options.targets.size() > static_cast<size_t>(scallop::load::kMaxTargets)) {
    std::cerr << "load_generator: at most " << scallop::load::kMaxTargets << " targets\n";
    return 2;
  }
  for (const std::string& target : options.targets) {
    if (!scallop::load::IsLoopbackTarget(target)) {
      std::cerr << "load_generator: --target must be a loopback address (127.x.x.x, localhost, "
                   "[::1]), got "
                << target << '\n';
      return 2;
    }
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
