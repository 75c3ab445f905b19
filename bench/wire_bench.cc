// The wire encodings of points (docs/wire.md) against today's packed arrays,
// in one run: bytes a point of the serialized Points message, and points a
// second through each side of the wire, with no network in between:
//   BM_Encode: scallopd's part, the points written into a message in the
//              encoding and serialized (what a warm GetPoints adds to a copy);
//   BM_Decode: the client's part, the bytes parsed and read into PlanePoints
//              (ReadPoints, as the client library does).
// Arguments: encoding (0 packed, 1 exact, 2 quantised), place (0 the origin,
// 1 1e6 d, 2 1e9 d: exact offsets take 7-8, 5 and 4 bytes there), rectangle
// side in d (64: a viewer's tile, 4 x 4 regions; 240: nearly a full page).
//
//   build/bench/wire_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <map>
#include <string>
#include <tuple>

#include "encoded_points.h"
#include "scallop/plane/plane_engine.h"
#include "world_messages.h"

namespace scallop {
namespace {

const World& BenchWorld() {
  static const World world = *World::Create({.seed = 7, .algorithm = WorldAlgorithm::kA3});
  return world;
}

constexpr double kPlaces[] = {0, 1e6, 1e9};
constexpr PointEncoding kEncodings[] = {PointEncoding::kPacked, PointEncoding::kExact,
                                        PointEncoding::kQuantised};

// The points of a square of `side` d with its lower-left corner at the place,
// off the region grid by a few d so edge regions are cut; generated once.
const PlanePoints& Points(int place, int side) {
  static std::map<std::pair<int, int>, PlanePoints> cache;
  auto [it, inserted] = cache.try_emplace({place, side});
  if (inserted) {
    PlaneEngine engine({.threads = 1});
    const double x0 = kPlaces[place] + 3.25, y0 = kPlaces[place] - 5.5;
    it->second = *engine.Points(BenchWorld(), {x0, y0, x0 + side, y0 + side});
  }
  return it->second;
}

std::string Serialized(PointEncoding encoding, const PlanePoints& points) {
  v1::Points message;
  AppendPoints(points, 0, points.ids.size(), message, BenchWorld(), encoding);
  return message.SerializeAsString();
}

void Report(benchmark::State& state, const PlanePoints& points, size_t bytes) {
  const auto count = static_cast<double>(points.ids.size());
  state.counters["points"] = count;
  state.counters["bytes_per_point"] = static_cast<double>(bytes) / count;
  state.counters["points_per_second"] = benchmark::Counter(
      count * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_Encode(benchmark::State& state) {
  const PointEncoding encoding = kEncodings[state.range(0)];
  const PlanePoints& points =
      Points(static_cast<int>(state.range(1)), static_cast<int>(state.range(2)));
  std::string bytes;
  for (auto _ : state) {
    v1::Points message;
    AppendPoints(points, 0, points.ids.size(), message, BenchWorld(), encoding);
    message.SerializeToString(&bytes);
    benchmark::DoNotOptimize(bytes.data());
  }
  Report(state, points, bytes.size());
}

void BM_Decode(benchmark::State& state) {
  const PointEncoding encoding = kEncodings[state.range(0)];
  const PlanePoints& points =
      Points(static_cast<int>(state.range(1)), static_cast<int>(state.range(2)));
  const std::string bytes = Serialized(encoding, points);
  for (auto _ : state) {
    v1::Points message;
    message.ParseFromString(bytes);
    PlanePoints decoded;
    if (!ReadPoints(message, decoded).ok()) state.SkipWithError("malformed");
    benchmark::DoNotOptimize(decoded.positions.data());
  }
  Report(state, points, bytes.size());
}

void Arguments(benchmark::internal::Benchmark* benchmark) {
  benchmark->ArgNames({"encoding", "place", "side"});
  for (int side : {64, 240}) {
    for (int place = 0; place < 3; ++place) {
      for (int encoding = 0; encoding < 3; ++encoding) benchmark->Args({encoding, place, side});
    }
  }
}

BENCHMARK(BM_Encode)->Apply(Arguments);
BENCHMARK(BM_Decode)->Apply(Arguments);

}  // namespace
}  // namespace scallop

BENCHMARK_MAIN();
