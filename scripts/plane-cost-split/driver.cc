// Where a cold plane query's time goes (docs/design.md, "Where a cold query's time goes"):
// runs cold queries on a one-thread engine built with counters.patch and prints each part's
// share of the time-stamp counter, with the work counts a returned point. Built and run by
// scripts/plane-cost-split.sh; not part of any build.
//
// Usage: driver [square side in d = 1000] [queries = 2] [tiles = 0: if > 0, that many cold
// tiles of the side at random places, as bench/cold_tile_latency makes them]
#include <cstdio>
#include <cstdlib>

#include "scallop/plane/plane_engine.h"
#include "scallop/plane/prof_counters.h"
#include "scallop/random/rng.h"

int main(int argc, char** argv) {
  using namespace scallop;
  const double side = argc > 1 ? std::atof(argv[1]) : 1000;
  const int queries = argc > 2 ? std::atoi(argv[2]) : 2;
  const int tiles = argc > 3 ? std::atoi(argv[3]) : 0;
  Rng rng(42);
  double returned = 0;
  const uint64_t start = prof::Now();
  for (int n = 0; n < (tiles > 0 ? tiles : queries); ++n) {
    PlaneEngine engine(PlaneEngineOptions{.cache_bytes = int64_t{4} << 30, .threads = 1});
    const World world = *World::Create({.seed = 500 + static_cast<uint64_t>(n)});
    const double x = tiles > 0 ? rng.Uniform(-1e4, 1e4) : 0,
                 y = tiles > 0 ? rng.Uniform(-1e4, 1e4) : 0;
    returned +=
        static_cast<double>(engine.Points(world, {x, y, x + side, y + side})->positions.size());
  }
  const double total = static_cast<double>(prof::Now() - start);
  const auto* c = prof::counters;
  auto share = [&](const char* what, double cycles) {
    std::printf("%-58s %5.1f%%\n", what, 100 * cycles / total);
  };
  auto count = [&](const char* what, double n) {
    std::printf("%-58s %6.3f a returned point\n", what, n / returned);
  };
  std::printf("%.0f points returned, %.0f counter ticks a point\n", returned, total / returned);
  share("A3, candidates placed by the run, in the region", c[prof::kCandInR]);
  share("A3, candidates placed by the run, outside it (spill)", c[prof::kCandOut]);
  share("A3, fixed points again (neighbours' points, in the region)", c[prof::kCandFixedIn]);
  share("A3, fixed points again (outside it)", c[prof::kCandFixedOut]);
  share("filing fixed and inert points (GatherNeighbourPoints)", c[prof::kGatherNeighbours]);
  share("the run's setup (grid, fixed and inert points into it)", c[prof::kSampleSetup]);
  share("A3's rest (grid construction, picks, the run's end)",
        c[prof::kSampleTotal] - c[prof::kSampleSetup] - c[prof::kCandInR] - c[prof::kCandOut] -
            c[prof::kCandFixedIn] - c[prof::kCandFixedOut]);
  share("storing the run's points (StorePlaced)", c[prof::kStore]);
  share("GenerateRegion's rest", c[prof::kGenerateRegion] - c[prof::kGatherNeighbours] -
                                     c[prof::kSampleTotal] - c[prof::kStore]);
  share("cache insertion (Publish)", c[prof::kPublish]);
  share("plan, lookups, locks (Resolve less generation)",
        c[prof::kResolve] - c[prof::kGenerateRegion] - c[prof::kPublish]);
  share("copy-out (VisitPoints)", c[prof::kVisit]);
  share("the rest (engines, worlds, freeing)", total - c[prof::kResolve] - c[prof::kVisit]);
  count("candidates placed by the run, in the region", c[prof::kNCandInR]);
  count("candidates placed by the run, outside it", c[prof::kNCandOut]);
  count("fixed points processed again", c[prof::kNCandFixedIn] + c[prof::kNCandFixedOut]);
  count("points placed in the region", c[prof::kNPlacedIn]);
  count("points placed outside it (spill)", c[prof::kNPlacedOut]);
  count("fixed points filed", c[prof::kNFixed]);
  count("inert points filed", c[prof::kNInert]);
  count("regions generated", c[prof::kRegions]);
  // Of the points a run flags as able to seed a later region (its fixed points to be):
  count("flagged: left in the pool when the region was covered", c[prof::kNLeft]);
  count("flagged: processed, the circle clipped by the sampled edge", c[prof::kNClipped]);
  return 0;
}
