// Layered worlds (issue 19): three layers (trees 8, bushes 3, rocks 1.5, the default matrix) on
// the infinite plane, cold, beside two baselines from the same run:
//  - a one-layer uniform A3 world of the smallest spacing (1.5), cold (the control);
//  - the studios' way: three passes of our bounded A3 sampler on the square (spacings 8, 3, 1.5,
//    each with its own seed), each pass's points dropped where they come within D of a point
//    kept by an earlier pass, through a grid; and the same passes taken from three uniform
//    worlds of the plane (cold), as a studio using the service would.
// Points per second of CPU time, and each layer's largest empty spot: the largest slack
// min(|x - q| - d_k, |x - c| - D) over a central window 20 or more from the square's edges (so
// that the bounded passes' edges and the plane's halo do not enter), probed d / 20 apart;
// positive means a point of that layer still fits there. Usage (docs/performance.md):
//   build/bench/layers_bench --benchmark_counters_tabular=true
// The page runs each benchmark's repetitions interleaved at random with the others'
// (--benchmark_enable_random_interleaving): the layered runs are the most memory-bound here, and
// a rival run minutes apart, under another load, moved their ratios by a fifth.
#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "scallop/plane/plane_engine.h"
#include "scallop/plane/world_layers.h"
#include "scallop/sampling/field_point_grid.h"
#include "scallop/sampling/sampler.h"
#include "scallop/verify/layer_verifier.h"

namespace scallop {
namespace {

World Forest() {
  WorldSpec spec{.seed = 2026};
  spec.layers = {{.name = "trees", .min_distance = 8},
                 {.name = "bushes", .min_distance = 3},
                 {.name = "rocks", .min_distance = 1.5}};
  return *World::Create(spec);
}

// A square holding about n points of the one-layer world of d = 1.5 (A3: 0.86 / d^2 a unit area;
// the forest's union is about as dense).
Rect SquareFor(int64_t n) {
  const double side = std::sqrt(static_cast<double>(n) / (0.86 / (1.5 * 1.5)));
  return {0.0, 0.0, side, side};
}

void Report(benchmark::State& state, int64_t produced) {
  state.SetItemsProcessed(state.iterations() * produced);
  state.counters["points"] = static_cast<double>(produced);
  state.counters["points_per_second"] = benchmark::Counter(
      static_cast<double>(produced), benchmark::Counter::kIsIterationInvariantRate);
}

using Counters = std::map<std::string, double>;

// Each layer's largest slack over the probe window (the central 150 x 150 of the square, or the
// square less 20 on every side if smaller), probed on a lattice d / 20 apart, in units of the
// layer's spacing d; and pairs closer than their rule (the layered verifier's count).
StatusOr<Counters> LargestEmptySpots(const World& world, const PlanePoints& points,
                                     const Rect& square) {
  Counters counters;
  const WorldLayers& layers = *world.layers();
  const double cx = 0.5 * (square.x0 + square.x1), cy = 0.5 * (square.y0 + square.y1);
  const double half = std::min(75.0, 0.5 * square.Width() - 20.0);
  const Rect probed{cx - half, cy - half, cx + half, cy + half};
  for (int k = 0; k < layers.count(); ++k) {
    const double d = layers.world(k).min_distance();
    // The layer's points with its spacing, the others with D to it: the slack at x is
    // min over all of |x - p| - radius.
    // A disk decides the slack at x only if it is the nearest by |x - c| - radius: within the
    // largest radius plus the slack itself. Disks are searched within 3 radii, so slacks up to
    // 2 radii are exact (a larger hole would read as infinity: a failure either way).
    double radius = 0.0;
    for (int j = 0; j < layers.count(); ++j) radius = std::max(radius, layers.exclusion(j, k));
    const double reach = 3 * radius;
    const Rect filed = Grown(probed, reach);
    FieldPointGrid disks(filed, radius);
    for (size_t m = 0; m < points.positions.size(); ++m) {
      if (filed.Contains(points.positions[m])) {
        disks.Add(points.positions[m], layers.exclusion(points.layers[m], k));
      }
    }
    double worst = -INFINITY;
    for (double y = probed.y0; y <= probed.y1; y += d / 20) {
      for (double x = probed.x0; x <= probed.x1; x += d / 20) {
        double slack = INFINITY;
        disks.AnyNear(Grown(Rect{x, y, x, y}, reach), [&](const FieldPoint& c) {
          slack = std::min(slack, std::sqrt(SquaredDistance(Vec2{x, y}, c.p)) - c.r);
          return false;
        });
        worst = std::max(worst, slack);
      }
    }
    counters["empty_" + layers.name(k) + "_in_d"] = worst / d;
  }
  std::vector<RadiusField> fields;
  std::vector<double> matrix;
  for (int a = 0; a < layers.count(); ++a) {
    fields.push_back(RadiusField::Constant(layers.world(a).min_distance()));
    for (int b = 0; b < layers.count(); ++b) matrix.push_back(layers.exclusion(a, b));
  }
  StatusOr<LayerVerifyReport> report =
      VerifyLayeredWindow(points.positions, points.layers, probed, fields, matrix);
  if (!report.ok()) return report.status();
  int64_t conflicts = report->cross_conflicts;
  for (const FieldVerifyReport& layer : report->layers) conflicts += layer.conflicts;
  counters["conflicts"] = static_cast<double>(conflicts);
  return counters;
}

// LargestEmptySpots' counters, computed at the first run of the benchmark `key` in the process
// only: every repetition makes the same points, and probing them takes longer than making them,
// which made the page's interleaved repetitions (above) too slow.
void ReportLargestEmptySpots(benchmark::State& state, const std::string& key, const World& world,
                             const PlanePoints& points, const Rect& square) {
  static std::map<std::string, StatusOr<Counters>> computed;
  auto found = computed.find(key);
  if (found == computed.end()) {
    found = computed.emplace(key, LargestEmptySpots(world, points, square)).first;
  }
  if (!found->second.ok()) {
    state.SkipWithError(found->second.status().message().c_str());
    return;
  }
  for (const auto& [name, value] : *found->second) state.counters[name] = value;
}

void BM_LayeredCold(benchmark::State& state) {
  const World world = Forest();
  const Rect square = SquareFor(state.range(0));
  PlanePoints last;
  for (auto _ : state) {
    PlaneEngine engine(PlaneEngineOptions{.threads = 1});
    StatusOr<PlanePoints> points = engine.Points(world, square);
    benchmark::DoNotOptimize(points->positions.data());
    last = *std::move(points);
  }
  Report(state, static_cast<int64_t>(last.positions.size()));
  ReportLargestEmptySpots(state, "layered" + std::to_string(state.range(0)), world, last, square);
}

// The same layers sampled on the square alone (SampleLayers), as a studio would run them over a
// bounded map: the apples-to-apples rival of the bounded passes below.
void BM_LayeredBounded(benchmark::State& state) {
  const World world = Forest();
  const Rect square = SquareFor(state.range(0));
  const LayeredSamplerOptions options = BoundedLayersOn(*world.layers(), square);
  PlanePoints last;
  for (auto _ : state) {
    StatusOr<LayeredPoints> sampled = SampleLayers(options);
    benchmark::DoNotOptimize(sampled->positions.data());
    last.positions = std::move(sampled->positions);
    last.layers = std::move(sampled->layers);
  }
  Report(state, static_cast<int64_t>(last.positions.size()));
  ReportLargestEmptySpots(state, "bounded" + std::to_string(state.range(0)), world, last, square);
}

void BM_UniformCold(benchmark::State& state) {
  const World world = *World::Create({.seed = 2026, .min_distance = 1.5});
  const Rect square = SquareFor(state.range(0));
  int64_t produced = 0;
  for (auto _ : state) {
    PlaneEngine engine(PlaneEngineOptions{.threads = 1});
    StatusOr<PlanePoints> points = engine.Points(world, square);
    produced = static_cast<int64_t>(points->positions.size());
    benchmark::DoNotOptimize(points->positions.data());
  }
  Report(state, produced);
}

// Where a studios' pass takes its points: bounded A3 on the square, or the square of a uniform
// world (a cold query of the plane engine), as a studio using the service would.
enum class PassSource { kBoundedA3, kPlane };

// The studios' passes: each layer's points at its spacing (its own seed), pruned against the
// kept points of earlier passes.
PlanePoints StudioPasses(const WorldLayers& layers, const Rect& square, uint64_t seed,
                         PassSource source) {
  PlanePoints kept;
  for (const int k : layers.generation_order()) {
    const double d = layers.world(k).min_distance();
    const uint64_t pass_seed = seed + static_cast<uint64_t>(k);
    std::vector<Vec2> pass;
    if (source == PassSource::kBoundedA3) {
      pass = *Sample({.algorithm = Algorithm::kA3,
                      .domain = {square, false},
                      .min_distance = d,
                      .seed = pass_seed});
    } else {
      PlaneEngine engine(PlaneEngineOptions{.threads = 1});
      pass =
          engine.Points(*World::Create({.seed = pass_seed, .min_distance = d}), square)->positions;
    }
    // The earlier passes' points, filed in cells of the largest D to this layer.
    double reach = 0.0;
    for (size_t m = 0; m < kept.positions.size(); ++m) {
      reach = std::max(reach, layers.exclusion(kept.layers[m], k));
    }
    FieldPointGrid earlier(square, std::max(reach, d));
    for (size_t m = 0; m < kept.positions.size(); ++m) {
      earlier.Add(kept.positions[m], layers.exclusion(kept.layers[m], k));
    }
    for (const Vec2& p : pass) {
      const bool pruned =
          earlier.AnyNear(Grown(Rect{p.x, p.y, p.x, p.y}, reach),
                          [&](const FieldPoint& c) { return SquaredDistance(p, c.p) < c.r * c.r; });
      if (pruned) continue;
      kept.positions.push_back(p);
      kept.layers.push_back(static_cast<uint8_t>(k));
    }
  }
  return kept;
}

void BM_StudioPasses(benchmark::State& state, PassSource source) {
  const World world = Forest();
  const Rect square = SquareFor(state.range(0));
  PlanePoints last;
  for (auto _ : state) {
    PlanePoints kept = StudioPasses(*world.layers(), square, 2026, source);
    benchmark::DoNotOptimize(kept.positions.data());
    last = std::move(kept);
  }
  Report(state, static_cast<int64_t>(last.positions.size()));
  const char* from = source == PassSource::kBoundedA3 ? "passes of bounded A3" : "passes of plane";
  ReportLargestEmptySpots(state, from + std::to_string(state.range(0)), world, last, square);
}

BENCHMARK(BM_LayeredCold)->Name("layers_cold_smoke")->Arg(5000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LayeredBounded)
    ->Name("layers_bounded_smoke")
    ->Arg(5000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_UniformCold)->Name("uniform_cold_smoke")->Arg(5000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_StudioPasses, bounded, PassSource::kBoundedA3)
    ->Name("studio_passes_smoke")
    ->Arg(5000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_StudioPasses, plane, PassSource::kPlane)
    ->Name("studio_plane_passes_smoke")
    ->Arg(5000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LayeredCold)->Name("layers_cold_250k")->Arg(250000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LayeredBounded)
    ->Name("layers_bounded_250k")
    ->Arg(250000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_UniformCold)->Name("uniform_cold_250k")->Arg(250000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_StudioPasses, bounded, PassSource::kBoundedA3)
    ->Name("studio_passes_250k")
    ->Arg(250000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_StudioPasses, plane, PassSource::kPlane)
    ->Name("studio_plane_passes_250k")
    ->Arg(250000)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace scallop

BENCHMARK_MAIN();
