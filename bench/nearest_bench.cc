// Noise-basis lookups per second on warm regions, beside a baseline from the
// same run: jittered-grid cellular (Worley) noise written here in
// FastNoiseLite's manner (hash of the cell -> a jitter vector, 3x3 cells,
// F1 and F2), which is what game tools use when they need no exact point set.
//
//   build/bench/nearest_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <vector>

#include "scallop/field/value_noise.h"
#include "scallop/noise/nearest_lookup.h"
#include "scallop/noise/noise_grid.h"
#include "scallop/random/rng.h"

namespace scallop {
namespace {

constexpr int kBatch = 1 << 16;      // positions per call (the server's default batch limit)
constexpr double kAreaSide = 256.0;  // in d: 16 x 16 regions, all cached before timing

// --- Baseline: jittered-grid cellular noise ---------------------------------
// One feature point per unit cell, jittered by a vector picked by a hash of
// the cell. FastNoiseLite's cellular noise is structured so; this code is
// ours. Frequency scales positions so that there are as many feature points
// per area as our A3 worlds have points per d^2 (about 0.86).
class JitteredGridCellular {
 public:
  explicit JitteredGridCellular(uint64_t seed) : seed_(static_cast<uint32_t>(seed)) {
    Rng rng(seed);
    for (auto& v : jitter_) {
      const double angle = rng.Uniform(0, 6.283185307179586);
      const double radius = 0.45 * std::sqrt(rng.Uniform());
      v = {static_cast<float>(radius * std::cos(angle)),
           static_cast<float>(radius * std::sin(angle))};
    }
  }

  struct Sample {
    float f1, f2;
    uint32_t cell_hash;
  };

  Sample Evaluate(double x, double y) const {
    const float fx = static_cast<float>(x * kFrequency), fy = static_cast<float>(y * kFrequency);
    const int rx = static_cast<int>(std::lround(fx)), ry = static_cast<int>(std::lround(fy));
    float d0 = 1e30f, d1 = 1e30f;
    uint32_t closest = 0;
    for (int cx = rx - 1; cx <= rx + 1; ++cx) {
      for (int cy = ry - 1; cy <= ry + 1; ++cy) {
        const uint32_t h = Hash(cx, cy);
        const Jitter& j = jitter_[h & 255];
        const float vx = static_cast<float>(cx) - fx + j.x, vy = static_cast<float>(cy) - fy + j.y;
        const float distance = vx * vx + vy * vy;
        // Branch-free F1/F2 update, as FastNoiseLite does it.
        d1 = std::fmax(std::fmin(d1, distance), d0);
        if (distance < d0) {
          d0 = distance;
          closest = h;
        }
      }
    }
    return {std::sqrt(d0), std::sqrt(d1), closest};
  }

 private:
  static constexpr double kFrequency = 0.927;  // sqrt(0.86): feature points per unit^2 = 0.86
  struct Jitter {
    float x, y;
  };
  uint32_t Hash(int cx, int cy) const {
    uint32_t h = seed_ ^ (static_cast<uint32_t>(cx) * 0x5205402bu) ^
                 (static_cast<uint32_t>(cy) * 0x1f4a7c15u);
    h *= 0x27d4eb2du;
    return h ^ (h >> 15);
  }
  uint32_t seed_;
  std::array<Jitter, 256> jitter_;
};

std::vector<Vec2> RandomPositions(uint64_t seed) {
  Rng rng(seed);
  std::vector<Vec2> positions(kBatch);
  for (Vec2& p : positions) p = {rng.Uniform(0, kAreaSide), rng.Uniform(0, kAreaSide)};
  return positions;
}

// Row-major samples of a 256 x 256 image of the area, as NoiseGrid asks.
std::vector<Vec2> ImagePositions() {
  std::vector<Vec2> positions;
  const double step = kAreaSide / 256;
  for (int r = 0; r < 256; ++r) {
    for (int c = 0; c < 256; ++c) positions.push_back({c * step, r * step});
  }
  return positions;
}

void SetLookupsPerSecond(benchmark::State& state) {
  state.counters["lookups_per_second"] = benchmark::Counter(
      static_cast<double>(kBatch), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_JitteredGridBaseline(benchmark::State& state) {
  const std::vector<Vec2> positions = state.range(0) ? ImagePositions() : RandomPositions(1);
  const JitteredGridCellular noise(7);
  std::vector<JitteredGridCellular::Sample> out(positions.size());
  for (auto _ : state) {
    for (size_t k = 0; k < positions.size(); ++k)
      out[k] = noise.Evaluate(positions[k].x, positions[k].y);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  SetLookupsPerSecond(state);
}
BENCHMARK(BM_JitteredGridBaseline)->ArgName("image_order")->Arg(0)->Arg(1);

// Warm lookups of `positions` in `world`, with the lookup's fallbacks and grid size.
void TimeWarmLookups(benchmark::State& state, const World& world,
                     const std::vector<Vec2>& positions, NearestLookupOptions options = {}) {
  PlaneEngine engine({.threads = 2});
  NearestLookup lookup(engine, options);
  std::vector<NearestPoint> out(positions.size());
  // Warm every region and grid of the area first: the figure is for warm lookups.
  if (!lookup.Nearest(world, positions, out).ok()) state.SkipWithError("lookup failed");
  for (auto _ : state) {
    if (!lookup.Nearest(world, positions, out).ok()) state.SkipWithError("lookup failed");
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  SetLookupsPerSecond(state);
  const NearestLookupStats stats = lookup.Stats();
  state.counters["fallbacks"] = static_cast<double>(stats.fallbacks);
  state.counters["grid_bytes_per_region"] =
      static_cast<double>(stats.bytes) / static_cast<double>(stats.grids_cached);
}

void BM_NearestWarm(benchmark::State& state) {
  TimeWarmLookups(state, *World::Create({.seed = 7}),
                  state.range(0) ? ImagePositions() : RandomPositions(1));
}
BENCHMARK(BM_NearestWarm)->ArgName("image_order")->Arg(0)->Arg(1);

// The same random positions through the SSE2 code, whatever this CPU has:
// what a CPU without AVX2 runs (docs/noise.md, "Speed").
void BM_NearestWarmTwoLanes(benchmark::State& state) {
  TimeWarmLookups(state, *World::Create({.seed = 7}), RandomPositions(1),
                  {.first_pass_width = NearestSearchGrid::FirstPassWidth::kTwoLanes});
}
BENCHMARK(BM_NearestWarmTwoLanes);

// Warm lookups on radius-field worlds (noise over [1, ratio], at 90% of the slope bound), the
// same positions in units of r_min, beside BM_NearestWarm's constant world (d = 1) in the same
// run: what FieldNearestGrid's ring search costs against the constant grid's quick pass.
void BM_NearestWarmField(benchmark::State& state) {
  const double ratio = static_cast<double>(state.range(0));
  WorldSpec spec{.seed = 7};
  spec.radius_field = RadiusFieldSpec{
      .kind = RadiusFieldKind::kNoise,
      .r_min = 1.0,
      .r_max = ratio,
      .noise_seed = 3,
      .frequency = 0.9 * kMaxFieldSlope / ((ratio - 1) * FractalValueNoiseSlope(1.0, 3, 0.5))};
  TimeWarmLookups(state, *World::Create(spec), RandomPositions(1));
}
BENCHMARK(BM_NearestWarmField)->ArgName("ratio")->Arg(4)->Arg(16);

// The same 256 x 256 image through EvaluateNoiseGrid (what the NoiseGrid RPC
// and `scallop noise` run): lookups plus building the image of one channel.
void BM_NoiseGridWarm(benchmark::State& state) {
  PlaneEngine engine({.threads = 2});
  NearestLookup lookup(engine);
  const World world = *World::Create({.seed = 7});
  const NoiseGridSpec spec{.origin = {0, 0},
                           .step = kAreaSide / 256,
                           .width = 256,
                           .height = 256,
                           .channel = NoiseChannel::kF1};
  if (!EvaluateNoiseGrid(lookup, world, spec, kBatch).ok()) state.SkipWithError("grid failed");
  for (auto _ : state) {
    StatusOr<NoiseImage> image = EvaluateNoiseGrid(lookup, world, spec, kBatch);
    if (!image.ok()) state.SkipWithError("grid failed");
    benchmark::DoNotOptimize(image->values.data());
  }
  SetLookupsPerSecond(state);
}
BENCHMARK(BM_NoiseGridWarm);

}  // namespace
}  // namespace scallop

BENCHMARK_MAIN();
