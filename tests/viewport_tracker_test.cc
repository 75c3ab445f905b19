// ViewportTracker against a brute-force follower: on random walks with
// reversals, teleports, zoom changes, keep margins and held regions, each
// point in view is held after every update, none is sent twice while its
// region is kept, evictions are exactly the held regions no longer kept, and
// the union of what was sent is the world's points over the path. Faults
// planted in the tracker's answers show that each check can fail.
#include "scallop/plane/viewport_tracker.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include "scallop/plane/point_id.h"
#include "scallop/random/rng.h"
#include "tests/test_worlds.h"

namespace scallop {
namespace {

// Half-open overlap, tested geometrically on the region's own rectangle:
// independent of the tracker's index arithmetic.
bool Overlaps(const Rect& a, const Rect& b) {
  return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

Rect GrownViewport(const ViewportUpdate& update) {
  const double m = update.keep_margin;
  const Rect& v = update.viewport;
  return {v.x0 - m, v.y0 - m, v.x1 + m, v.y1 + m};
}

// Every region whose rectangle overlaps `rect`, by brute force over a
// generous index range.
std::set<RegionKey> RegionsOverlappingByBruteForce(const World& world, const Rect& rect) {
  const RegionLayout layout(world.min_distance());
  std::set<RegionKey> keys;
  const auto lo_i = static_cast<int64_t>(std::floor(rect.x0 / layout.side())) - 1;
  const auto hi_i = static_cast<int64_t>(std::floor(rect.x1 / layout.side())) + 1;
  const auto lo_j = static_cast<int64_t>(std::floor(rect.y0 / layout.side())) - 1;
  const auto hi_j = static_cast<int64_t>(std::floor(rect.y1 / layout.side())) + 1;
  for (int64_t j = lo_j; j <= hi_j; ++j) {
    for (int64_t i = lo_i; i <= hi_i; ++i) {
      if (Overlaps(layout.RegionRect({i, j}), rect)) keys.insert({i, j});
    }
  }
  return keys;
}

// What the tracker answered to one update.
struct Answer {
  std::vector<RegionKey> evicted;
  std::vector<RegionChunk> chunks;
};

// The follower: the points it holds, by region, as a client would store them.
struct Follower {
  std::map<RegionKey, std::map<uint64_t, Vec2>> held;
};

std::string Key(RegionKey key) {
  std::ostringstream text;  // not string concatenation: GCC 12 -Wrestrict misfires on it
  text << '(' << key.i << ", " << key.j << ')';
  return text.str();
}

// Applies `answer` to `follower` and returns the first contract violation,
// or "" when there is none. `in_view` is the engine's answer for the viewport.
std::string ApplyAndCheck(const World& world, const ViewportUpdate& update,
                          const PlanePoints& in_view, const Answer& answer, Follower& follower) {
  const std::set<RegionKey> kept = RegionsOverlappingByBruteForce(world, GrownViewport(update));
  std::vector<RegionKey> should_evict;
  for (const auto& [key, points] : follower.held) {
    if (!kept.contains(key)) should_evict.push_back(key);
  }
  if (answer.evicted != should_evict) {
    return "evicted " + std::to_string(answer.evicted.size()) + " regions, expected " +
           std::to_string(should_evict.size());
  }
  for (const RegionKey& key : answer.evicted) follower.held.erase(key);
  for (const RegionChunk& chunk : answer.chunks) {
    for (size_t n = 0; n < chunk.points.ids.size(); ++n) {
      const uint64_t id = chunk.points.ids[n];
      const Vec2 p = chunk.points.positions[n];
      if (DecodePointId(id, chunk.key).region != chunk.key) {
        return "point " + std::to_string(id) + " sent in the chunk of region " + Key(chunk.key);
      }
      if (!update.viewport.Contains(p)) return "point " + std::to_string(id) + " is out of view";
      if (!follower.held[chunk.key].emplace(id, p).second) {
        return "point " + std::to_string(id) + " sent twice while its region was kept";
      }
    }
  }
  const RegionLayout layout(world.min_distance());
  for (size_t n = 0; n < in_view.ids.size(); ++n) {
    const Vec2 p = in_view.positions[n];
    const RegionKey region = DecodePointId(in_view.ids[n], layout.RegionOf(p.x, p.y)).region;
    const auto it = follower.held.find(region);
    if (it == follower.held.end() || !it->second.contains(in_view.ids[n])) {
      return "point " + std::to_string(in_view.ids[n]) + " in view is not held";
    }
  }
  for (const auto& [key, points] : follower.held) {
    if (!kept.contains(key)) return "region " + Key(key) + " held but not kept";
  }
  return "";
}

// A random path of `steps` viewports: a steady walk with reversals,
// teleports (some to the edge of the precision range), zoom changes, random
// keep margins; with `held`, also regions declared held and resumed sessions.
struct PathStep {
  ViewportUpdate update;
  bool resume = false;  // start a new tracker (a new session) first
  int load_held = 0;    // kept regions the follower loads whole and declares
};

std::vector<PathStep> RandomPath(Rng& rng, const World& world, int steps, bool held) {
  const double d = world.min_distance();
  const double limit = RegionLayout(d).precision_limit();
  double w = rng.Uniform(4, 40) * d, h = rng.Uniform(4, 40) * d;
  double cx = rng.Uniform(-1e4, 1e4) * d, cy = rng.Uniform(-1e4, 1e4) * d;
  double vx = rng.Uniform(-5, 5) * d, vy = rng.Uniform(-5, 5) * d;
  std::vector<PathStep> path;
  for (int step = 0; step < steps; ++step) {
    PathStep next;
    switch (rng.Below(12)) {
      case 0:  // teleport, a fifth of them to the edge of the precision range
        if (rng.Below(5) == 0) {
          cx = (rng.Below(2) ? 1 : -1) * limit;
          cy = rng.Uniform(-1e6, 1e6) * d;
        } else {
          cx = rng.Uniform(-1e6, 1e6) * d;
          cy = rng.Uniform(-1e6, 1e6) * d;
        }
        break;
      case 1:  // reversal
        vx = -vx;
        vy = -vy;
        break;
      case 2:  // zoom
        w = std::clamp(w * rng.Uniform(0.5, 2), 1 * d, 48 * d);
        h = std::clamp(h * rng.Uniform(0.5, 2), 1 * d, 48 * d);
        break;
      case 3:
        next.resume = held;
        next.load_held = held ? 2 : 0;
        break;
      case 4:
        next.load_held = held ? 1 : 0;
        break;
      default:
        break;
    }
    cx = std::clamp(cx + vx, -limit + w / 2, limit - w / 2);
    cy = std::clamp(cy + vy, -limit + h / 2, limit - h / 2);
    next.update.viewport = {cx - w / 2, cy - h / 2, cx + w / 2, cy + h / 2};
    next.update.velocity = {vx * 30, vy * 30};  // 30 updates a second
    next.update.keep_margin = rng.Below(3) == 0 ? 0.0 : rng.Uniform(0, 12) * d;
    path.push_back(next);
  }
  return path;
}

// Follows `path` with a tracker and a brute-force follower; `tamper` may
// alter the tracker's answer to an update (returns true once it did). The
// first violation, prefixed by its step; "" when none. Also checks that the
// union of the points sent equals the world's points over the path (when no
// held regions are declared, the case where the two must be equal).
std::string FollowPath(PlaneEngine& engine, const World& world, Rng& rng,
                       const std::vector<PathStep>& path,
                       const std::function<void(Answer&, const ViewportUpdate&)>& tamper = {}) {
  ViewportTracker tracker(world);
  Follower follower;
  std::set<uint64_t> received, in_view_union;
  bool declared_held = false;
  for (size_t step = 0; step < path.size(); ++step) {
    ViewportUpdate update = path[step].update;
    const std::string where = "step " + std::to_string(step) + ": ";
    if (Status status = ValidateViewportUpdate(world, update, 1e5); !status.ok()) {
      return where + status.message();
    }
    if (path[step].resume) {
      tracker = ViewportTracker(world);
      follower = {};
    }
    if (path[step].load_held > 0) {
      // Regions in view: kept, and within the precision range.
      const std::set<RegionKey> kept_set = RegionsOverlappingByBruteForce(world, update.viewport);
      const std::vector<RegionKey> kept(kept_set.begin(), kept_set.end());
      for (int n = 0; n < path[step].load_held; ++n) {
        const RegionKey key = kept[rng.Below(kept.size())];
        StatusOr<RegionHandle> region = engine.Region(world, key);
        if (!region.ok()) return where + region.status().message();
        for (size_t k = 0; k < (*region)->points.size(); ++k) {
          follower.held[key][EncodePointId(key, static_cast<uint32_t>(k))] = (*region)->points[k];
        }
        update.held_regions.push_back(key);
      }
      // A held region far away is ignored: the follower does not store it.
      update.held_regions.push_back({rng.Uniform() < 0.5 ? -7 : 1 << 20, 3});
      declared_held = true;
    }
    Answer answer;
    answer.evicted = tracker.Update(update);
    StatusOr<PlanePoints> in_view = engine.Points(world, update.viewport);
    if (!in_view.ok()) return where + in_view.status().message();
    StatusOr<std::vector<RegionChunk>> chunks = tracker.TakeUnsent(*in_view);
    if (!chunks.ok()) return where + chunks.status().message();
    answer.chunks = std::move(*chunks);
    if (tamper) tamper(answer, update);
    for (const RegionChunk& chunk : answer.chunks) {
      received.insert(chunk.points.ids.begin(), chunk.points.ids.end());
    }
    in_view_union.insert(in_view->ids.begin(), in_view->ids.end());
    if (std::string violation = ApplyAndCheck(world, update, *in_view, answer, follower);
        !violation.empty()) {
      return where + violation;
    }
    std::vector<RegionKey> held_keys;
    for (const auto& [key, points] : follower.held) held_keys.push_back(key);
    if (tracker.HeldRegions() != held_keys) return where + "HeldRegions differs from the follower";
  }
  if (!declared_held && received != in_view_union) {
    return "the union of the points sent (" + std::to_string(received.size()) +
           ") differs from the world's points over the path (" +
           std::to_string(in_view_union.size()) + ")";
  }
  return "";
}

// The tracker only sees ids and positions, so the algorithm does not matter
// to it; the scale of d does (region arithmetic). A3 is the cheapest to generate.
std::vector<World> TestWorlds(uint64_t seed) {
  return {ValidWorld({.seed = seed}), ValidWorld({.seed = seed, .min_distance = 0.37}),
          ValidWorld({.seed = seed, .min_distance = 1000})};
}

TEST(ViewportTrackerTest, RandomWalksHoldEveryPointInViewOnceAndEvictExactly) {
  PlaneEngine engine({.threads = 1});
  for (uint64_t seed = 1; seed <= 3; ++seed) {
    for (const World& world : TestWorlds(seed)) {
      for (const bool held : {false, true}) {
        Rng rng(HashWords({seed, static_cast<uint64_t>(world.algorithm()), held}));
        const std::vector<PathStep> path = RandomPath(rng, world, 30, held);
        EXPECT_EQ(FollowPath(engine, world, rng, path), "")
            << "seed " << seed << ", " << world.Describe() << ", held " << held;
      }
    }
  }
}

// Each check of FollowPath must catch a fault planted in real answers.
TEST(ViewportTrackerTest, PlantedFaultsAreCaught) {
  const World world = ValidWorld({.seed = 11});
  PlaneEngine engine({.threads = 1});
  struct Fault {
    const char* name;
    const char* expected;                                       // part of the violation message
    std::function<bool(Answer&, const ViewportUpdate&)> plant;  // true once planted
  };
  const std::vector<Fault> faults{
      {"a point left out", "in view is not held",
       [](Answer& a, const ViewportUpdate&) {
         for (RegionChunk& chunk : a.chunks) {
           if (chunk.points.ids.empty()) continue;
           chunk.points.ids.pop_back();
           chunk.points.positions.pop_back();
           return true;
         }
         return false;
       }},
      {"a point sent twice", "sent twice",
       [](Answer& a, const ViewportUpdate&) {
         if (a.chunks.empty()) return false;
         a.chunks.push_back(a.chunks.front());
         return true;
       }},
      {"an eviction left out", "evicted",
       [](Answer& a, const ViewportUpdate&) {
         if (a.evicted.empty()) return false;
         a.evicted.pop_back();
         return true;
       }},
      {"a kept region evicted", "evicted",
       [](Answer& a, const ViewportUpdate&) {
         if (a.chunks.empty()) return false;
         a.evicted.push_back(a.chunks.front().key);
         return true;
       }},
      {"a chunk with the wrong key", "chunk of region",
       [](Answer& a, const ViewportUpdate&) {
         if (a.chunks.empty()) return false;
         a.chunks.front().key.i += 1;
         return true;
       }},
      {"a point out of view", "out of view",
       [](Answer& a, const ViewportUpdate& u) {
         if (a.chunks.empty()) return false;
         a.chunks.front().points.positions.front().x = u.viewport.x1;
         return true;
       }},
  };
  for (const Fault& fault : faults) {
    Rng rng(5);
    const std::vector<PathStep> path = RandomPath(rng, world, 40, false);
    bool planted = false;
    const std::string violation =
        FollowPath(engine, world, rng, path, [&](Answer& answer, const ViewportUpdate& update) {
          // Plant once, at the first answer the fault applies to.
          if (!planted) planted = fault.plant(answer, update);
        });
    EXPECT_TRUE(planted) << fault.name;
    EXPECT_NE(violation.find(fault.expected), std::string::npos)
        << fault.name << ": got '" << violation << "'";
  }
}

TEST(ViewportTrackerTest, RegionsReturningAfterEvictionAreSentAgain) {
  const World world = ValidWorld({.seed = 2});
  PlaneEngine engine({.threads = 1});
  ViewportTracker tracker(world);
  const ViewportUpdate here{.viewport = {0, 0, 20, 20}};
  const ViewportUpdate far{.viewport = {1000, 0, 1020, 20}};
  auto sent = [&](const ViewportUpdate& update) {
    tracker.Update(update);
    size_t count = 0;
    const StatusOr<std::vector<RegionChunk>> chunks =
        tracker.TakeUnsent(*engine.Points(world, update.viewport));
    for (const RegionChunk& chunk : *chunks) {
      count += chunk.points.ids.size();
    }
    return count;
  };
  const size_t first = sent(here);
  EXPECT_GT(first, 0u);
  EXPECT_EQ(sent(here), 0u);  // nothing new while nothing moved
  sent(far);
  EXPECT_EQ(sent(here), first);  // evicted, so sent again
}

TEST(ViewportTrackerTest, HeldRegionsAreNeverSent) {
  const World world = ValidWorld({.seed = 4});
  PlaneEngine engine({.threads = 1});
  ViewportTracker tracker(world);
  ViewportUpdate update{.viewport = {-10, -10, 10, 10}, .held_regions = {{-1, -1}, {0, 0}}};
  tracker.Update(update);
  const StatusOr<std::vector<RegionChunk>> chunks =
      tracker.TakeUnsent(*engine.Points(world, update.viewport));
  ASSERT_TRUE(chunks.ok());
  for (const RegionChunk& chunk : *chunks) {
    EXPECT_TRUE(chunk.key == (RegionKey{-1, 0}) || chunk.key == (RegionKey{0, -1}))
        << "region " << chunk.key.i << ", " << chunk.key.j;
  }
  EXPECT_EQ(tracker.HeldRegions(), (std::vector<RegionKey>{{-1, -1}, {-1, 0}, {0, -1}, {0, 0}}));
}

TEST(ViewportTrackerTest, PrefetchAreaLooksAheadAtMostOneViewport) {
  const World world = ValidWorld({.seed = 1, .min_distance = 2});
  const ViewportTracker tracker(world);
  ViewportUpdate still{.viewport = {0, 0, 64, 32}};
  EXPECT_FALSE(tracker.PrefetchArea(still).has_value());
  ViewportUpdate slow = still;
  slow.velocity = {10, -5};
  EXPECT_EQ(*tracker.PrefetchArea(slow), (Rect{10, -5, 74, 27}));
  ViewportUpdate fast = still;
  fast.velocity = {-1e9, 1e300};
  EXPECT_EQ(*tracker.PrefetchArea(fast), (Rect{-64, 32, 0, 64}));
  // At the edge of the precision range the prediction is clipped, and
  // dropped when nothing of it is left.
  const double limit = 0x1.0p32 * 2;
  ViewportUpdate edge{.viewport = {limit - 64, 0, limit, 32}, .velocity = {100, 0}};
  EXPECT_FALSE(tracker.PrefetchArea(edge).has_value());
  edge.velocity = {100, 10};
  EXPECT_FALSE(tracker.PrefetchArea(edge).has_value());
  edge.viewport.x0 = limit - 128;
  EXPECT_EQ(*tracker.PrefetchArea(edge), (Rect{limit - 28, 10, limit, 42}));
  // Random velocities: the prediction always touches the viewport.
  Rng rng(17);
  for (int n = 0; n < 1000; ++n) {
    ViewportUpdate update{.viewport = {0, 0, rng.Uniform(1, 100), rng.Uniform(1, 100)},
                          .velocity = {rng.Uniform(-500, 500), rng.Uniform(-500, 500)}};
    const Rect ahead = *tracker.PrefetchArea(update);
    const Rect& v = update.viewport;
    EXPECT_TRUE(ahead.x0 <= v.x1 && v.x0 <= ahead.x1 && ahead.y0 <= v.y1 && v.y0 <= ahead.y1);
  }
}

TEST(ViewportTrackerTest, BadUpdatesAreRejectedNamingTheField) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const World world = ValidWorld({.seed = 1, .min_distance = 0.5});
  const ViewportUpdate good{.viewport = {0, 0, 10, 10}, .velocity = {1, 2}, .keep_margin = 3};
  ASSERT_TRUE(ValidateViewportUpdate(world, good, 2000).ok());
  struct Case {
    const char* name;
    std::function<void(ViewportUpdate&)> spoil;
    StatusCode code;
    const char* field;
  };
  using enum StatusCode;
  const std::vector<Case> cases{
      {"nan x0", [&](ViewportUpdate& u) { u.viewport.x0 = nan; }, kInvalidArgument,
       "viewport.x0: must be finite"},
      {"infinite y1", [&](ViewportUpdate& u) { u.viewport.y1 = inf; }, kInvalidArgument,
       "viewport.y1: must be finite"},
      {"inverted x", [](ViewportUpdate& u) { u.viewport.x0 = 20; }, kInvalidArgument,
       "viewport: x0 must be less than x1"},
      {"empty y", [](ViewportUpdate& u) { u.viewport.y1 = 0; }, kInvalidArgument,
       "viewport: y0 must be less than y1"},
      {"beyond the range", [](ViewportUpdate& u) { u.viewport.y0 = -0x1.0p32; }, kOutOfRange,
       "viewport.y0: |value| must be at most"},
      {"nan velocity", [&](ViewportUpdate& u) { u.velocity.x = nan; }, kInvalidArgument,
       "velocity_x: must be finite"},
      {"infinite velocity", [&](ViewportUpdate& u) { u.velocity.y = -inf; }, kInvalidArgument,
       "velocity_y: must be finite"},
      {"negative margin", [](ViewportUpdate& u) { u.keep_margin = -1; }, kInvalidArgument,
       "keep_margin: must be finite and >= 0"},
      {"nan margin", [&](ViewportUpdate& u) { u.keep_margin = nan; }, kInvalidArgument,
       "keep_margin"},
      {"huge margin", [](ViewportUpdate& u) { u.keep_margin = 1e308; }, kInvalidArgument,
       "max_follow_area"},
      {"margin over the area", [](ViewportUpdate& u) { u.keep_margin = 10; }, kInvalidArgument,
       "viewport grown by keep_margin: area is"},
      {"viewport over the area", [](ViewportUpdate& u) { u.viewport.x1 = 100; }, kInvalidArgument,
       "max_follow_area"},
      {"thin viewport over many regions",
       [](ViewportUpdate& u) {
         u.viewport = {0, 0, 1e6, 1e-9};
         u.keep_margin = 0;
       },
       kInvalidArgument, "regions"},
  };
  for (const Case& c : cases) {
    ViewportUpdate update = good;
    c.spoil(update);
    const Status status = ValidateViewportUpdate(world, update, 2000);
    EXPECT_EQ(status.code(), c.code) << c.name << ": " << status.message();
    EXPECT_NE(status.message().find(c.field), std::string::npos)
        << c.name << ": " << status.message();
  }
}

}  // namespace
}  // namespace scallop
