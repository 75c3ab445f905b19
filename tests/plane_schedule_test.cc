// The engine's schedule: a region is generated as soon as its own lower-ranked
// neighbours are, not rank by rank. Checked two ways: a query's points, ids
// and layers equal a one-thread engine's and a fresh engine's, for random
// rectangles on engines of many threads shared by concurrent callers; and,
// through a RegionGenerationObserver, no region starts before each of its
// lower-ranked neighbours has finished, and none is generated twice.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "scallop/plane/plane_engine.h"
#include "scallop/plane/region_generator.h"
#include "scallop/random/rng.h"
#include "tests/layer_checks.h"
#include "tests/test_worlds.h"

namespace scallop {
namespace {

PlaneEngineOptions Options(int threads, int64_t cache_bytes = int64_t{256} << 20,
                           RegionGenerationObserver* observer = nullptr) {
  return {.cache_bytes = cache_bytes, .threads = threads, .observer = observer};
}

// An A3, an A1 and a layered world (whose later layers' regions wait for the
// earlier layers' regions too), from `seed`.
std::vector<World> ScheduleWorlds(uint64_t seed) {
  Rng dice(seed);
  return {DiceWorld(dice, WorldAlgorithm::kA3, 1.0), DiceWorld(dice, WorldAlgorithm::kA1, 0.37),
          Forest(dice.NextBits())};
}

// A rectangle of 4 to 56 spacings a side (of the world's smallest spacing)
// within 3000 of them of the origin.
Rect RandomRect(Rng& rng, const World& world) {
  const double d = world.layers() != nullptr ? 1.5 : world.min_distance();
  const double x0 = d * rng.Uniform(-3000, 3000), y0 = d * rng.Uniform(-3000, 3000);
  return {x0, y0, x0 + d * rng.Uniform(4, 56), y0 + d * rng.Uniform(4, 56)};
}

// A query's answer as bits: ids, coordinates' bit patterns and layers.
using Answer = std::vector<std::tuple<uint64_t, uint64_t, uint64_t, int>>;

Answer Bits(const StatusOr<PlanePoints>& points) {
  Answer answer;
  if (!points.ok()) return answer;
  for (size_t k = 0; k < points->positions.size(); ++k) {
    answer.emplace_back(points->ids[k], std::bit_cast<uint64_t>(points->positions[k].x),
                        std::bit_cast<uint64_t>(points->positions[k].y),
                        points->layers.empty() ? -1 : points->layers[k]);
  }
  return answer;
}

std::string Describe(const World& world, const Rect& r) {
  std::ostringstream out;
  out.precision(17);
  out << world.Describe() << ", rect [" << r.x0 << ", " << r.x1 << ") x [" << r.y0 << ", " << r.y1
      << ")";
  return out.str();
}

// Four callers share an engine of six threads (kept across the queries, so
// it carries a history) and one of five on a cache of about six regions
// (which evicts regions other queries still need); each asks its own random
// rectangles. Every answer must equal a fresh one-thread engine's and a
// fresh six-thread engine's, bit for bit.
TEST(PlaneScheduleTest, ManyThreadsGiveTheBitsOfOneThread) {
  constexpr uint64_t kSeed = 0x5c4ed;
  SCOPED_TRACE(::testing::Message() << "seed " << kSeed);
  const std::vector<World> worlds = ScheduleWorlds(kSeed);
  PlaneEngine shared(Options(6));
  PlaneEngine evicting(Options(5, 24 << 10));
  constexpr int kCallers = 4, kQueries = 4;
  std::vector<std::vector<std::string>> failures(kCallers);
  std::vector<std::thread> callers;
  for (int c = 0; c < kCallers; ++c) {
    callers.emplace_back([&, c] {
      Rng rng(HashWords({kSeed, static_cast<uint64_t>(c)}));
      for (int q = 0; q < kQueries; ++q) {
        const World& world = worlds[rng.Below(worlds.size())];
        const Rect rect = RandomRect(rng, world);
        PlaneEngine alone(Options(1));
        PlaneEngine fresh(Options(6));
        const Answer expected = Bits(alone.Points(world, rect));
        const char* differs = expected.size() < 5                              ? "too few points"
                              : Bits(fresh.Points(world, rect)) != expected    ? "fresh engine"
                              : Bits(shared.Points(world, rect)) != expected   ? "shared engine"
                              : Bits(evicting.Points(world, rect)) != expected ? "evicting engine"
                                                                               : nullptr;
        if (differs != nullptr)
          failures[c].push_back(std::string(differs) + ": caller " + std::to_string(c) +
                                ", query " + std::to_string(q) + ", " + Describe(world, rect));
      }
    });
  }
  for (std::thread& caller : callers) caller.join();
  for (const std::vector<std::string>& caller : failures) {
    for (const std::string& failure : caller) ADD_FAILURE() << failure;
  }
  EXPECT_GT(evicting.CacheStats().evictions, 0);
}

// What the observer saw, in one order for all threads.
struct GenerationEvent {
  uint64_t world;  // fingerprint
  RegionKey key;
  bool started;  // else finished
};

class GenerationLog : public RegionGenerationObserver {
 public:
  void Started(const World& world, RegionKey key) override {
    Add({world.fingerprint(), key, true});
  }
  void Finished(const World& world, RegionKey key) override {
    Add({world.fingerprint(), key, false});
  }
  std::vector<GenerationEvent> events() const {
    std::lock_guard lock(mutex_);
    return events_;
  }

 private:
  void Add(const GenerationEvent& event) {
    std::lock_guard lock(mutex_);
    events_.push_back(event);
  }
  mutable std::mutex mutex_;
  std::vector<GenerationEvent> events_;
};

// The first fault in a log of an engine that never evicts, or "": a region
// started before one of its lower-ranked neighbours finished (or without it
// ever finishing), started twice, or never finished.
std::string FirstScheduleFault(const std::vector<GenerationEvent>& log) {
  auto where = [](const GenerationEvent& e) {
    return "region " + std::to_string(e.key.i) + "," + std::to_string(e.key.j) + " of world " +
           std::to_string(e.world);
  };
  auto find = [&](size_t end, uint64_t world, RegionKey key, bool started) {
    for (size_t k = 0; k < end; ++k) {
      if (log[k].world == world && log[k].key == key && log[k].started == started) return k;
    }
    return end;
  };
  for (size_t k = 0; k < log.size(); ++k) {
    const GenerationEvent& e = log[k];
    if (!e.started) continue;
    if (find(k, e.world, e.key, true) < k) return where(e) + " started twice";
    const size_t finish = find(log.size(), e.world, e.key, false);
    if (finish < k || finish == log.size()) return where(e) + " did not finish after it started";
    for (const RegionKey& n : LowerRankedNeighbours(e.key)) {
      if (find(k, e.world, n, false) == k) {
        return where(e) + " started before its neighbour " + std::to_string(n.i) + "," +
               std::to_string(n.j) + " finished";
      }
    }
  }
  return "";
}

// Three callers share an engine of four threads with overlapping random
// rectangles of the three worlds; the log of every generation must show no
// fault, and a region generated for each miss.
TEST(PlaneScheduleTest, NoRegionStartsBeforeItsLowerRankedNeighboursFinish) {
  constexpr uint64_t kSeed = 0x0b5e7;
  SCOPED_TRACE(::testing::Message() << "seed " << kSeed);
  const std::vector<World> worlds = ScheduleWorlds(kSeed);
  GenerationLog log;
  PlaneEngine engine(Options(4, int64_t{256} << 20, &log));
  std::vector<std::thread> callers;
  for (int c = 0; c < 3; ++c) {
    callers.emplace_back([&, c] {
      Rng rng(HashWords({kSeed, static_cast<uint64_t>(c)}));
      for (int q = 0; q < 4; ++q) {
        const World& world = worlds[q % worlds.size()];
        // Near the origin, so the callers' queries share regions.
        const double d = world.layers() != nullptr ? 1.5 : world.min_distance();
        const double x0 = d * rng.Uniform(-60, 60), y0 = d * rng.Uniform(-60, 60);
        EXPECT_TRUE(engine.Points(world, {x0, y0, x0 + 64 * d, y0 + 64 * d}).ok());
      }
    });
  }
  for (std::thread& caller : callers) caller.join();
  const std::vector<GenerationEvent> events = log.events();
  EXPECT_EQ(FirstScheduleFault(events), "");
  EXPECT_EQ(static_cast<int64_t>(events.size()), 2 * engine.CacheStats().misses);
  EXPECT_EQ(engine.CacheStats().evictions, 0);
  ASSERT_GT(events.size(), 400u);

  // Planted faults the check must catch, in the real log: a region's start
  // moved before its first neighbour's finish; a start repeated; a finish lost.
  size_t moved = 0;
  while (moved < events.size() &&
         !(events[moved].started && !LowerRankedNeighbours(events[moved].key).empty())) {
    ++moved;
  }
  ASSERT_LT(moved, events.size());
  std::vector<GenerationEvent> early = events;
  const GenerationEvent start = early[moved];
  early.erase(early.begin() + static_cast<std::ptrdiff_t>(moved));
  early.insert(early.begin(), start);
  EXPECT_NE(FirstScheduleFault(early).find("before its neighbour"), std::string::npos);
  std::vector<GenerationEvent> twice = events;
  twice.push_back(start);
  EXPECT_NE(FirstScheduleFault(twice).find("started twice"), std::string::npos);
  std::vector<GenerationEvent> unfinished = events;
  std::erase_if(unfinished, [&](const GenerationEvent& e) {
    return !e.started && e.world == start.world && e.key == start.key;
  });
  EXPECT_NE(FirstScheduleFault(unfinished), "");
}

}  // namespace
}  // namespace scallop
