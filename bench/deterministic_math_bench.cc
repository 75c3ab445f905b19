// Speed of scallop/base/deterministic_math.h against glibc's libm on the same inputs, in one run,
// both as throughput (independent calls over an array) and latency (each call waits for the
// last). The run ends with a table of glibc time / our time per function (> 1: we are faster).
//
//   build-math/bench/deterministic_math_bench --benchmark_repetitions=20
//     --benchmark_min_time=0.05 --benchmark_enable_random_interleaving=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "scallop/base/deterministic_math.h"
#include "scallop/random/rng.h"

namespace scallop {
namespace {

constexpr int kInputs = 4096;  // fits in L1 with the outputs, so memory is not what we time

// Inputs like the samplers': angles in [-pi, pi] (sin, cos), displacements in a disk of radius
// about 2 (atan2), ratios of such (atan) and cosines (acos, asin).
struct Inputs {
  std::vector<double> a, b;
};
Inputs MakeInputs(const std::string& kind) {
  Rng rng(42);
  Inputs in;
  for (int i = 0; i < kInputs; ++i) {
    if (kind == "angle") {
      in.a.push_back(rng.Uniform(-std::numbers::pi, std::numbers::pi));
    } else if (kind == "wide_angle") {
      in.a.push_back(rng.Uniform(-8 * std::numbers::pi, 8 * std::numbers::pi));
    } else if (kind == "unit") {
      in.a.push_back(rng.Uniform(-1.0, 1.0));
    } else if (kind == "ratio") {
      in.a.push_back(rng.Uniform(-2.0, 2.0) / rng.Uniform(0.01, 2.0));
    } else {  // "plane"
      in.a.push_back(rng.Uniform(-2.0, 2.0));
      in.b.push_back(rng.Uniform(-2.0, 2.0));
    }
  }
  return in;
}

template <typename F>
void Throughput(benchmark::State& state, const char* kind, F f) {
  const Inputs in = MakeInputs(kind);
  std::vector<double> out(kInputs);
  for (auto _ : state) {
    for (int i = 0; i < kInputs; ++i) out[i] = f(in, i, 0.0);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kInputs);
}

// Each input is nudged by the previous result times 2^-70 (below an ulp of every input here, so
// the arguments are the throughput ones, but the call must wait for the previous one): one
// dependency chain, as when an angle feeds the next computation.
template <typename F>
void Latency(benchmark::State& state, const char* kind, F f) {
  const Inputs in = MakeInputs(kind);
  double carry = 0.0;
  for (auto _ : state) {
    for (int i = 0; i < kInputs; ++i) carry = f(in, i, carry * 0x1p-70);
    benchmark::DoNotOptimize(carry);
  }
  state.SetItemsProcessed(state.iterations() * kInputs);
}

// `ours` and `glibc` are expressions in the input arrays `in`, the index `i` and the nudge `e`
// (0.0 for throughput, where GCC folds x - 0.0 to x, so no extra instruction is timed).
#define SCALLOP_MATH_BENCH(name, kind, ours, glibc)                               \
  void BM_##name##_Throughput_Ours(benchmark::State& s) {                         \
    Throughput(s, kind, [](const Inputs& in, int i, double e) { return ours; });  \
  }                                                                               \
  void BM_##name##_Throughput_Glibc(benchmark::State& s) {                        \
    Throughput(s, kind, [](const Inputs& in, int i, double e) { return glibc; }); \
  }                                                                               \
  void BM_##name##_Latency_Ours(benchmark::State& s) {                            \
    Latency(s, kind, [](const Inputs& in, int i, double e) { return ours; });     \
  }                                                                               \
  void BM_##name##_Latency_Glibc(benchmark::State& s) {                           \
    Latency(s, kind, [](const Inputs& in, int i, double e) { return glibc; });    \
  }                                                                               \
  BENCHMARK(BM_##name##_Throughput_Ours);                                         \
  BENCHMARK(BM_##name##_Throughput_Glibc);                                        \
  BENCHMARK(BM_##name##_Latency_Ours);                                            \
  BENCHMARK(BM_##name##_Latency_Glibc)

#define A (in.a[i] - e)
#define B (in.b[i])

SCALLOP_MATH_BENCH(Atan2, "plane", DetAtan2(A, B), std::atan2(A, B));
SCALLOP_MATH_BENCH(Atan, "ratio", DetAtan(A), std::atan(A));
SCALLOP_MATH_BENCH(Sin, "angle", DetSin(A), std::sin(A));
SCALLOP_MATH_BENCH(Cos, "angle", DetCos(A), std::cos(A));
SCALLOP_MATH_BENCH(SinWide, "wide_angle", DetSin(A), std::sin(A));
SCALLOP_MATH_BENCH(SinCos, "angle", ([&] {
                     double s, c;
                     DetSinCos(A, &s, &c);
                     return s + c;
                   }()),
                   ([&] {
                     double s, c;
                     sincos(A, &s, &c);
                     return s + c;
                   }()));
SCALLOP_MATH_BENCH(Asin, "unit", DetAsin(A), std::asin(A));
SCALLOP_MATH_BENCH(Acos, "unit", DetAcos(A), std::acos(A));

#undef A
#undef B

// Prints the usual table, then glibc time / our time for each pair. With --benchmark_repetitions
// it takes each benchmark's fastest repetition: other work on the machine only ever adds time, so
// the minimum is the steadiest estimate of the code's own cost (and random interleaving keeps the
// two sides of a pair under the same conditions).
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      if (run.run_type != Run::RT_Iteration || run.error_occurred) continue;
      const std::string name = run.run_name.function_name;
      const double ns = run.GetAdjustedCPUTime() / kInputs;  // the default unit is ns
      const auto split = name.rfind('_');
      auto& side = name.substr(split + 1) == "Ours" ? ours_ : glibc_;
      const auto [it, inserted] = side.emplace(name.substr(0, split), ns);
      if (!inserted) it->second = std::min(it->second, ns);
    }
  }
  void Finalize() override {
    ConsoleReporter::Finalize();
    std::printf("\n%-28s %12s %12s %10s\n", "function", "ours ns/call", "glibc", "glibc/ours");
    for (const auto& [name, ours] : ours_) {
      const auto glibc = glibc_.find(name);
      if (glibc == glibc_.end()) continue;
      std::printf("%-28s %12.2f %12.2f %10.2f\n", name.c_str(), ours, glibc->second,
                  glibc->second / ours);
    }
  }

 private:
  std::map<std::string, double> ours_, glibc_;
};

}  // namespace
}  // namespace scallop

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  scallop::RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}
