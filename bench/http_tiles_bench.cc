// Warm tiles over HTTP against the same tiles by GetPoints, in one run,
// against one real scallopd (started as the end-to-end tests start it, with
// --http-listen): a square of tiles is fetched once to warm the region
// cache, then every tile is asked again and again by each way, the same
// rectangles in the same order, by `streams` clients at once (each with one
// keep-alive HTTP connection, or one gRPC channel). The ways take turns,
// REPEATS times (each a pass of ROUNDS over the square), so that load from
// elsewhere on the machine falls on all of them alike, and each way's median
// pass is reported: tiles a second, microseconds a tile, bytes a tile, and
// its ratio to GetPoints.
//
//   build/bench/http_tiles_bench [LEVEL [TILES_A_SIDE [ROUNDS [STREAMS [REPEATS]]]]]
//   build/bench/http_tiles_bench 1 16 4 1 7   # the defaults
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "bench/http_connection.h"
#include "scallop/plane/region_layout.h"
#include "scallop_client.h"
#include "tests/e2e/scallopd_process.h"
#include "world_messages.h"

namespace scallop {
namespace {

struct TileAt {
  int64_t i = 0;
  int64_t j = 0;
};

struct Way {
  std::string name;
  // Fetches tile `tile` once on the calling stream's connection; returns its bytes.
  std::function<size_t(int stream, const TileAt& tile)> fetch;
};

struct Measured {
  double seconds = 0;
  int64_t tiles = 0;
  int64_t bytes = 0;
};

// Every tile `rounds` times, split among `streams` threads (stream s takes
// tiles s, s + streams, ...).
Measured Run(const Way& way, const std::vector<TileAt>& tiles, int rounds, int streams) {
  std::vector<int64_t> bytes(streams, 0);
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::thread> threads;
  for (int s = 0; s < streams; ++s) {
    threads.emplace_back([&, s] {
      for (int round = 0; round < rounds; ++round) {
        for (size_t k = s; k < tiles.size(); k += streams) {
          bytes[s] += static_cast<int64_t>(way.fetch(s, tiles[k]));
        }
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  Measured measured;
  measured.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  measured.tiles = static_cast<int64_t>(tiles.size()) * rounds;
  for (const int64_t b : bytes) measured.bytes += b;
  return measured;
}

std::string CpuModel() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.starts_with("model name")) return line.substr(line.find(':') + 2);
  }
  return "unknown";
}

int Main(int argc, char** argv) {
  const int level = argc > 1 ? std::atoi(argv[1]) : 1;
  const int side = argc > 2 ? std::atoi(argv[2]) : 16;
  const int rounds = argc > 3 ? std::atoi(argv[3]) : 4;
  const int streams = argc > 4 ? std::atoi(argv[4]) : 1;
  const int repeats = argc > 5 ? std::atoi(argv[5]) : 7;
  if (level < 0 || level > 5 || side < 1 || rounds < 1 || streams < 1 || repeats < 1) {
    std::fprintf(
        stderr,
        "usage: http_tiles_bench [LEVEL 0..5 [TILES_A_SIDE [ROUNDS [STREAMS [REPEATS]]]]]\n");
    return 2;
  }
  auto server = testing::ScallopdProcess::Start(
      {"--http-listen", "127.0.0.1:0", "--log-level", "warn", "--threads", "2"});
  if (!server) return 1;
  const std::string http_address = server->ReadAnnouncedAddress("scallopd http on ");
  if (http_address.empty()) return 1;

  // The square of tiles centred on the origin, row by row.
  std::vector<TileAt> tiles;
  for (int j = -side / 2; j < side - side / 2; ++j) {
    for (int i = -side / 2; i < side - side / 2; ++i) tiles.push_back({i, j});
  }
  const double tile_side = kRegionSideInD * std::ldexp(1.0, level);  // d = 1
  auto target = [&](const TileAt& tile, const char* extension) {
    return "/v1/worlds/default/tiles/" + std::to_string(tile.i) + "/" + std::to_string(tile.j) +
           extension + "?level=" + std::to_string(level);
  };

  std::vector<std::unique_ptr<HttpConnection>> connections;
  std::vector<client::ScallopClient> clients;
  for (int s = 0; s < streams; ++s) {
    connections.push_back(std::make_unique<HttpConnection>(http_address));
    clients.push_back(server->Client());
  }
  auto http_way = [&](const char* name, const char* extension) {
    return Way{name, [&, extension](int s, const TileAt& tile) {
                 std::string body;
                 if (connections[s]->Get(target(tile, extension), body) != 200) std::abort();
                 return body.size();
               }};
  };
  const Way get_points{"GetPoints", [&](int s, const TileAt& tile) {
                         v1::GetPointsRequest request;
                         *request.mutable_rect() =
                             RectToMessage({tile.i * tile_side, tile.j * tile_side,
                                            (tile.i + 1) * tile_side, (tile.j + 1) * tile_side});
                         v1::GetPointsResponse response;
                         if (!clients[s].GetPoints(request, response).ok()) std::abort();
                         return response.ByteSizeLong();
                       }};
  // Revalidation: what a browser or proxy with the tile pays to learn it is current.
  std::vector<std::string> etags(tiles.size());
  for (size_t k = 0; k < tiles.size(); ++k) {
    std::string body;
    connections[0]->Get(target(tiles[k], ".bin"), body);  // warms the regions too
    etags[k] = connections[0]->last_etag();
  }
  const Way not_modified{
      "HTTP 304 (If-None-Match)", [&](int s, const TileAt& tile) {
        const size_t k = static_cast<size_t>((tile.j + side / 2) * side + (tile.i + side / 2));
        std::string body;
        if (connections[s]->Get(target(tile, ".bin"), body, etags[k]) != 304) {
          std::abort();
        }
        return body.size();
      }};
  const std::vector<Way> ways = {get_points, http_way("HTTP binary (.bin)", ".bin"),
                                 http_way("HTTP JSON (.json)", ".json"),
                                 http_way("HTTP PNG (.png)", ".png"), not_modified};
  // One untimed round of each way: connections, caches and pages are warm.
  for (const Way& way : ways) Run(way, tiles, 1, streams);

  std::printf(
      "# http_tiles_bench: %zu warm tiles of level %d (%g d a side), %d passes of %d rounds "
      "each, median pass; %d stream(s); scallopd --threads 2; CPU: %s\n",
      tiles.size(), level, tile_side, repeats, rounds, streams, CpuModel().c_str());
  std::vector<std::vector<Measured>> passes(ways.size());
  for (int repeat = 0; repeat < repeats; ++repeat) {
    for (size_t w = 0; w < ways.size(); ++w)
      passes[w].push_back(Run(ways[w], tiles, rounds, streams));
  }
  std::printf("%-26s %10s %12s %10s %12s %14s\n", "way", "tiles/pass", "tiles/s", "us/tile",
              "bytes/tile", "vs GetPoints");
  double baseline = 0;
  for (size_t w = 0; w < ways.size(); ++w) {
    std::vector<Measured>& measured = passes[w];
    std::sort(measured.begin(), measured.end(),
              [](const Measured& a, const Measured& b) { return a.seconds < b.seconds; });
    const Measured& median = measured[measured.size() / 2];
    const double rate = static_cast<double>(median.tiles) / median.seconds;
    if (baseline == 0) baseline = rate;
    std::printf("%-26s %10lld %12.0f %10.1f %12.0f %13.2fx\n", ways[w].name.c_str(),
                static_cast<long long>(median.tiles), rate,
                1e6 * median.seconds / static_cast<double>(median.tiles) * streams,
                static_cast<double>(median.bytes) / static_cast<double>(median.tiles),
                rate / baseline);
  }
  return 0;
}

}  // namespace
}  // namespace scallop

int main(int argc, char** argv) { return scallop::Main(argc, argv); }
