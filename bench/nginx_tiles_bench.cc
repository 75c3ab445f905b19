// nginx's tile cache (deploy/nginx/scallop.conf, run as e2e_nginx_test runs
// it) in front of one real scallopd (--http-listen, --threads 2), in one run:
//
// 1. Cold against hit: every tile of a square is asked once through nginx (a
//    MISS: scallopd generates its regions, nginx stores the answer), then
//    once more (a HIT that no replica sees). Median microseconds a tile of
//    each, and their ratio.
// 2. Through nginx against direct: the same, now warm, tiles again and again,
//    from nginx's cache and from scallopd itself (regions in its cache), one
//    keep-alive connection each, the two ways taking turns REPEATS times so
//    that load from elsewhere falls on both alike. Tiles a second of each
//    way's median pass, and the ratio.
//
//   build/bench/nginx_tiles_bench [LEVEL [TILES_A_SIDE [ROUNDS [REPEATS]]]]
//   build/bench/nginx_tiles_bench 1 16 4 7   # the defaults
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/http_connection.h"
#include "tests/e2e/nginx_process.h"
#include "tests/e2e/scallopd_process.h"

namespace scallop {
namespace {

double Median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// Seconds `fetch` takes, by the steady clock.
double Seconds(const std::function<void()>& fetch) {
  const auto start = std::chrono::steady_clock::now();
  fetch();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

int Main(int argc, char** argv) {
  const int level = argc > 1 ? std::atoi(argv[1]) : 1;
  const int side = argc > 2 ? std::atoi(argv[2]) : 16;
  const int rounds = argc > 3 ? std::atoi(argv[3]) : 4;
  const int repeats = argc > 4 ? std::atoi(argv[4]) : 7;
  if (level < 0 || level > 5 || side < 1 || rounds < 1 || repeats < 1) {
    std::fprintf(stderr,
                 "usage: nginx_tiles_bench [LEVEL 0..5 [TILES_A_SIDE [ROUNDS [REPEATS]]]]\n");
    return 2;
  }
  auto server = testing::ScallopdProcess::Start(
      {"--http-listen", "127.0.0.1:0", "--log-level", "warn", "--threads", "2"});
  if (!server) return 1;
  const std::string direct_address = server->ReadAnnouncedAddress("scallopd http on ");
  auto nginx = testing::NginxProcess::Start(
      SCALLOP_NGINX_CONFIG,
      {{"scallopd_grpc", {server->address()}}, {"scallopd_http", {direct_address}}});
  if (direct_address.empty() || !nginx) return 1;
  HttpConnection direct(direct_address), cached(nginx->Address(8090));

  std::vector<std::string> targets;  // the square centred on the origin, row by row
  for (int j = -side / 2; j < side - side / 2; ++j) {
    for (int i = -side / 2; i < side - side / 2; ++i) {
      targets.push_back("/v1/worlds/default/tiles/" + std::to_string(i) + "/" + std::to_string(j) +
                        ".bin?level=" + std::to_string(level));
    }
  }
  // Asks `target` on `connection`, and throws unless the answer is 200 with
  // the X-Cache-Status `cache` (empty: direct, none).
  auto fetch = [](HttpConnection& connection, const std::string& target, const char* cache) {
    std::string body;
    if (connection.Get(target, body) != 200 || connection.last_cache_status() != cache) {
      throw std::runtime_error(target + ": not a 200 " + cache + " (X-Cache-Status '" +
                               connection.last_cache_status() + "')");
    }
    return body.size();
  };

  std::vector<double> cold, hit;
  size_t bytes = 0;
  for (const std::string& target : targets) {
    cold.push_back(Seconds([&] { bytes += fetch(cached, target, "MISS"); }));
    hit.push_back(Seconds([&] { fetch(cached, target, "HIT"); }));
  }
  std::printf(
      "# nginx_tiles_bench: %zu tiles of level %d (%d d a side, %zu bytes a tile on average, "
      ".bin); scallopd --threads 2 behind nginx on deploy/nginx/scallop.conf\n",
      targets.size(), level, 16 << level, bytes / targets.size());
  const double cold_us = 1e6 * Median(cold), hit_us = 1e6 * Median(hit);
  std::printf("%-34s %12.1f us/tile\n", "cold tile through nginx (MISS)", cold_us);
  std::printf("%-34s %12.1f us/tile   %.1fx faster than cold\n", "cache hit through nginx (HIT)",
              hit_us, cold_us / hit_us);

  std::vector<double> direct_passes, cached_passes;
  for (int repeat = 0; repeat < repeats; ++repeat) {
    direct_passes.push_back(Seconds([&] {
      for (int round = 0; round < rounds; ++round) {
        for (const std::string& target : targets) fetch(direct, target, "");
      }
    }));
    cached_passes.push_back(Seconds([&] {
      for (int round = 0; round < rounds; ++round) {
        for (const std::string& target : targets) fetch(cached, target, "HIT");
      }
    }));
  }
  const double tiles = static_cast<double>(targets.size()) * rounds;
  const double direct_rate = tiles / Median(direct_passes);
  const double cached_rate = tiles / Median(cached_passes);
  std::printf("# warm: %d passes of %d rounds, median pass, one keep-alive connection each\n",
              repeats, rounds);
  std::printf("%-34s %12.0f tiles/s\n", "direct from scallopd (warm)", direct_rate);
  std::printf("%-34s %12.0f tiles/s   %.2fx direct\n", "through nginx (HIT)", cached_rate,
              cached_rate / direct_rate);
  return 0;
}

}  // namespace
}  // namespace scallop

// A failed fetch ends the run through main, so that nginx and scallopd are
// stopped by their destructors rather than left running by an abort.
int main(int argc, char** argv) {
  try {
    return scallop::Main(argc, argv);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "nginx_tiles_bench: %s\n", error.what());
    return 1;
  }
}
