// soak_load: a bounded mixed load on one scallopd for scripts/soak.sh. Worker
// threads, one connection each, loop until the duration ends over a fixed mix
// of calls: GetPoints (single pages and paged, warm and at fresh places),
// StreamPoints (read whole or cancelled after the first chunk), Follow
// (a short walk, sometimes abandoned mid-answer), Nearest and NoiseGrid,
// calls with a deadline too short to finish, and bad inputs. Each kind of
// call has the codes it may end with; RESOURCE_EXHAUSTED (load shedding) is
// allowed everywhere and counted. Any other code is an error: the first few
// are printed, and the exit status is 1 if there was one.
//
//   soak_load --target 127.0.0.1:50051 --duration 60 --workers 6 --seed 1
#include <grpcpp/grpcpp.h>

#include <CLI/CLI.hpp>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <mutex>
#include <random>
#include <set>
#include <thread>

#include "bench/loopback_target.h"
#include "follow_client.h"
#include "scallop_client.h"
#include "world_messages.h"

namespace scallop::load {
namespace {

using Clock = std::chrono::steady_clock;
using grpc::StatusCode;

struct SoakOptions {
  std::string target = "127.0.0.1:50051";
  double duration_seconds = 60;
  int workers = 6;
  uint64_t seed = 1;
};

constexpr double kMaxDurationSeconds = 24 * 3600;
constexpr int kMaxWorkers = 64;
constexpr int kErrorsPrinted = 10;

// The mix: each worker draws one of these per iteration, uniformly.
enum class CallKind {
  kWarmPage,       // GetPoints, one page near the origin (cached after the first)
  kColdPage,       // GetPoints at a fresh place: fills and churns the cache
  kPagedRead,      // GetPoints page after page with small pages (page tokens)
  kStreamWhole,    // StreamPoints read to the end
  kStreamCancel,   // StreamPoints cancelled after the first chunk
  kFollowWalk,     // Follow: a few viewport updates, then a clean finish
  kFollowAbandon,  // Follow: one update sent, the call dropped without reading
  kNearest,        // Nearest at scattered positions
  kNoiseGrid,      // a small NoiseGrid
  kShortDeadline,  // a cold GetPoints with a 1 ms deadline
  kBadInput,       // an invalid request: must be refused with the right code
  kCount
};
constexpr std::array<const char*, static_cast<size_t>(CallKind::kCount)> kKindNames = {
    "warm_page",      "cold_page", "paged_read", "stream_whole",   "stream_cancel", "follow_walk",
    "follow_abandon", "nearest",   "noise_grid", "short_deadline", "bad_input"};

struct KindTally {
  std::atomic<int64_t> calls{0};
  std::atomic<int64_t> shed{0};  // RESOURCE_EXHAUSTED
};

class Soak {
 public:
  explicit Soak(const SoakOptions& options) : options_(options) {}

  int Run() {
    const Clock::time_point stop =
        Clock::now() + std::chrono::duration_cast<Clock::duration>(
                           std::chrono::duration<double>(options_.duration_seconds));
    {
      std::vector<std::jthread> workers;
      for (int w = 0; w < options_.workers; ++w) {
        workers.emplace_back([this, w, stop] { Work(w, stop); });
      }
    }
    int64_t calls = 0;
    for (size_t k = 0; k < tallies_.size(); ++k) {
      std::cout << "soak_load " << kKindNames[k] << ": " << tallies_[k].calls << " calls, "
                << tallies_[k].shed << " shed\n";
      calls += tallies_[k].calls;
    }
    std::cout << "soak_load: " << calls << " calls, " << errors_ << " errors\n";
    return errors_ == 0 && calls > 0 ? 0 : 1;
  }

 private:
  // One worker: its own connection and generator (seeded from the run seed
  // and the worker's number, so a run can be replayed call for call).
  void Work(int worker, Clock::time_point stop) {
    grpc::ChannelArguments arguments;
    arguments.SetInt(GRPC_ARG_USE_LOCAL_SUBCHANNEL_POOL, 1);
    client::ScallopClient client(
        grpc::CreateCustomChannel(options_.target, grpc::InsecureChannelCredentials(), arguments));
    std::mt19937_64 random(options_.seed * 1000003 + static_cast<uint64_t>(worker));
    while (Clock::now() < stop) {
      const auto kind = static_cast<CallKind>(random() % static_cast<uint64_t>(CallKind::kCount));
      ++tallies_[static_cast<size_t>(kind)].calls;
      Call(client, kind, random);
    }
  }

  // Uniform in [lo, hi): our own, since std::uniform_real_distribution's
  // values differ across standard libraries and a seed should replay.
  static double Uniform(std::mt19937_64& random, double lo, double hi) {
    return lo + (hi - lo) * static_cast<double>(random() >> 11) * 0x1p-53;
  }

  static v1::Rect Square(double x, double y, double side) {
    return RectToMessage(Rect{x, y, x + side, y + side});
  }

  static client::CallOptions Timeout(int milliseconds) {
    return {.timeout = std::chrono::milliseconds(milliseconds)};
  }

  void Call(client::ScallopClient& client, CallKind kind, std::mt19937_64& random) {
    // Places for cold calls: far apart in a range of 2^24 d, so that the
    // cache keeps evicting.
    const double far_x = Uniform(random, -0x1p24, 0x1p24);
    const double far_y = Uniform(random, -0x1p24, 0x1p24);
    switch (kind) {
      case CallKind::kWarmPage: {
        v1::GetPointsRequest request;
        *request.mutable_rect() = Square(Uniform(random, 0, 192), Uniform(random, 0, 192), 64);
        v1::GetPointsResponse response;
        Expect(kind, client.GetPoints(request, response, Timeout(30000)), {StatusCode::OK});
        break;
      }
      case CallKind::kColdPage: {
        v1::GetPointsRequest request;
        *request.mutable_rect() = Square(far_x, far_y, 128);
        v1::GetPointsResponse response;
        Expect(kind, client.GetPoints(request, response, Timeout(30000)), {StatusCode::OK});
        break;
      }
      case CallKind::kPagedRead: {
        v1::GetPointsRequest request;
        *request.mutable_rect() = Square(far_x, far_y, 48);
        request.set_page_size(static_cast<int32_t>(50 + random() % 400));
        PlanePoints points;
        Expect(kind, client.GetAllPoints(request, points, Timeout(30000)), {StatusCode::OK});
        break;
      }
      case CallKind::kStreamWhole:
      case CallKind::kStreamCancel: {
        v1::StreamPointsRequest request;
        *request.mutable_rect() = Square(far_x, far_y, 256);
        const bool cancel = kind == CallKind::kStreamCancel;
        const grpc::Status status = client.StreamPoints(
            request, [cancel](const v1::PointsChunk&) { return !cancel; }, Timeout(60000));
        Expect(kind, status, {cancel ? StatusCode::CANCELLED : StatusCode::OK});
        break;
      }
      case CallKind::kFollowWalk: {
        client::FollowSession session(client, Timeout(60000));
        grpc::Status status;
        for (int step = 0; step < 4 && status.ok(); ++step) {
          v1::FollowRequest request;
          *request.mutable_viewport() = Square(far_x + 24 * step, far_y, 96);
          request.set_velocity_x(24);
          status = session.Update(request, [](const v1::FollowResponse&) {});
        }
        Expect(kind, status.ok() ? session.Finish() : status, {StatusCode::OK});
        break;
      }
      case CallKind::kFollowAbandon: {
        // The session's destructor cancels the call with answers unread.
        client::FollowSession session(client, Timeout(60000));
        v1::FollowRequest request;
        *request.mutable_viewport() = Square(far_x, far_y, 128);
        session.SendOnly(request);
        break;
      }
      case CallKind::kNearest: {
        v1::NearestRequest request;
        for (int k = 0; k < 256; ++k) {
          // Spread over a 128 x 128 region square: a bounded number of regions.
          request.mutable_positions()->add_xs(far_x + Uniform(random, 0, 2048));
          request.mutable_positions()->add_ys(far_y + Uniform(random, 0, 2048));
        }
        v1::NearestResponse response;
        Expect(kind, client.Nearest(request, response, Timeout(30000)), {StatusCode::OK});
        break;
      }
      case CallKind::kNoiseGrid: {
        v1::NoiseGridRequest request;
        request.set_origin_x(far_x);
        request.set_origin_y(far_y);
        request.set_step(0.25);
        request.set_width(128);
        request.set_height(128);
        request.set_channel(v1::NOISE_CHANNEL_F2_MINUS_F1);
        v1::NoiseGridResponse response;
        Expect(kind, client.NoiseGrid(request, response, Timeout(30000)), {StatusCode::OK});
        break;
      }
      case CallKind::kShortDeadline: {
        v1::GetPointsRequest request;
        *request.mutable_rect() = Square(far_x, far_y, 512);
        v1::GetPointsResponse response;
        Expect(kind, client.GetPoints(request, response, Timeout(1)),
               {StatusCode::OK, StatusCode::DEADLINE_EXCEEDED});
        break;
      }
      case CallKind::kBadInput:
        CallBadInput(client, random);
        break;
      case CallKind::kCount:
        break;
    }
  }

  // One of a few invalid requests, each with the code the API promises.
  void CallBadInput(client::ScallopClient& client, std::mt19937_64& random) {
    const CallKind kind = CallKind::kBadInput;
    v1::GetPointsRequest request;
    *request.mutable_rect() = Square(0, 0, 16);
    StatusCode expected = StatusCode::INVALID_ARGUMENT;
    switch (random() % 5) {
      case 0:
        request.mutable_rect()->set_x1(std::numeric_limits<double>::quiet_NaN());
        break;
      case 1:
        request.set_world_name(std::string(1 + random() % 20000, 'w') + std::string("\n\0x", 3));
        expected = StatusCode::NOT_FOUND;
        break;
      case 2:
        request.set_page_token("not a token");
        break;
      case 3:
        *request.mutable_rect() = Square(0, 0, 1e5);  // past max_query_area
        break;
      default:
        request.mutable_world()->set_min_distance(-1);
        break;
    }
    v1::GetPointsResponse response;
    Expect(kind, client.GetPoints(request, response, Timeout(30000)), {expected});
  }

  void Expect(CallKind kind, const grpc::Status& status,
              std::initializer_list<StatusCode> allowed) {
    if (status.error_code() == StatusCode::RESOURCE_EXHAUSTED) {
      ++tallies_[static_cast<size_t>(kind)].shed;
      return;
    }
    for (StatusCode code : allowed) {
      if (status.error_code() == code) return;
    }
    const int64_t count = ++errors_;
    if (count <= kErrorsPrinted) {
      std::lock_guard lock(print_mutex_);
      std::cerr << "soak_load: " << kKindNames[static_cast<size_t>(kind)]
                << " failed: " << client::DescribeStatus(status) << '\n';
    }
  }

  const SoakOptions options_;
  std::array<KindTally, static_cast<size_t>(CallKind::kCount)> tallies_;
  std::atomic<int64_t> errors_{0};
  std::mutex print_mutex_;
};

}  // namespace
}  // namespace scallop::load

int main(int argc, char** argv) {
  scallop::load::SoakOptions options;
  CLI::App app{"soak_load: a bounded mixed load on scallopd (scripts/soak.sh)"};
  app.add_option("--target", options.target, "HOST:PORT, loopback only")->capture_default_str();
  app.add_option("--duration", options.duration_seconds, "Seconds of load")
      ->check(CLI::Range(0.1, scallop::load::kMaxDurationSeconds))
      ->capture_default_str();
  app.add_option("--workers", options.workers, "Concurrent workers (a connection each)")
      ->check(CLI::Range(1, scallop::load::kMaxWorkers))
      ->capture_default_str();
  app.add_option("--seed", options.seed, "Seed of the call mix and places")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  if (!scallop::load::IsLoopbackTarget(options.target)) {
    std::cerr << "soak_load: --target must be a loopback address, got " << options.target << '\n';
    return 2;
  }
  std::cout << "soak_load: seed " << options.seed << ", " << options.workers << " workers, "
            << options.duration_seconds << " s against " << options.target << std::endl;
  return scallop::load::Soak(options).Run();
}
