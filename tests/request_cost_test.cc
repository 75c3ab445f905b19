// What Nearest and NoiseGrid calls cost before admission (server/request_cost.h), on the
// worlds whose reads differ: a constant world and a field world without masks read their
// positions' regions' grids (the 3 x 3 regions about each, counted as the positions' regions,
// in the world's own regions: 6 r_max for a field); a field world with masks may also read the
// brute force's square of half side 32 r_max about a position near a mask, so its cost must
// cover every region that square overlaps. Checked against region counts worked out here
// from RegionLayout, not from the cost code.
#include "server/request_cost.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

#include "scallop/noise/nearest_lookup.h"
#include "scallop/plane/query_rect.h"
#include "tests/field_test_fields.h"

namespace scallop::server {
namespace {

using field_test::FieldCase;

// The regions a square of half side `half` about p overlaps in `world`.
double RegionsAbout(const World& world, Vec2 p, double half) {
  return RegionsOverlapping(RegionLayout(world), {p.x - half, p.y - half, p.x + half, p.y + half})
      .Count();
}

WorldRegistry Registry() {
  std::map<std::string, World> worlds;
  worlds.emplace("plain", ValidWorld({.seed = 1, .min_distance = 1.0}));
  worlds.emplace("dunes", field_test::PlaneWorld(FieldCase::kNoise, 2, 1.0, 4.0));
  worlds.emplace("holes", field_test::PlaneWorld(FieldCase::kMaskedRaster, 3, 1.0, 4.0));
  return WorldRegistry(std::move(worlds), "plain");
}

v1::NearestRequest NearestAt(const std::string& world, std::initializer_list<Vec2> positions) {
  v1::NearestRequest request;
  request.set_world_name(world);
  for (const Vec2& p : positions) {
    request.mutable_positions()->add_xs(p.x);
    request.mutable_positions()->add_ys(p.y);
  }
  return request;
}

TEST(RequestCostTest, NearestCountsTheWorldsOwnRegions) {
  const WorldRegistry worlds = Registry();
  // One position: one region, in any world without masks.
  EXPECT_EQ(RequestCost(worlds, NearestAt("plain", {{3, 3}}), 4096), 1);
  EXPECT_EQ(RequestCost(worlds, NearestAt("dunes", {{3, 3}}), 4096), 1);
  // Two positions 40 apart: 16 d regions 0..2 on x (3 regions, capped at the 2 positions);
  // a field world's 24-wide regions 0..1 (2 regions).
  EXPECT_EQ(RequestCost(worlds, NearestAt("plain", {{3, 3}, {43, 3}}), 4096), 2);
  EXPECT_EQ(RequestCost(worlds, NearestAt("dunes", {{3, 3}, {43, 3}}), 4096), 2);
  // Many positions in one field region cost that region, not their number.
  EXPECT_EQ(RequestCost(worlds, NearestAt("dunes", {{1, 1}, {5, 9}, {20, 20}, {23, 2}}), 4096), 1);
}

TEST(RequestCostTest, MaskedFieldWorldsCoverTheFallbacksSquare) {
  const WorldRegistry worlds = Registry();
  ResolvedWorld holes;
  v1::NearestRequest by_name = NearestAt("holes", {});
  ASSERT_TRUE(worlds.Resolve(by_name, holes).ok());
  ASSERT_TRUE(holes.world.radius_field()->HasMask());
  const double reach = NearestLookup::FallbackReach(holes.world);
  EXPECT_EQ(reach, 32 * 4.0);
  for (const Vec2 p : {Vec2{3, 3}, Vec2{-30.5, 11}, Vec2{0, 0}}) {
    const int64_t cost = RequestCost(worlds, NearestAt("holes", {p}), 4096);
    // Every region the brute force's square may read, and no more than that square's.
    EXPECT_GE(static_cast<double>(cost), RegionsAbout(holes.world, p, reach)) << p.x;
    EXPECT_LE(static_cast<double>(cost), RegionsAbout(holes.world, p, reach) + 2 * 12 + 1) << p.x;
  }
  // Two positions far apart: each one's square (the grown box would be larger).
  const Vec2 a{0, 0}, b{5000, 0};
  const int64_t two = RequestCost(worlds, NearestAt("holes", {a, b}), 4096);
  EXPECT_GE(static_cast<double>(two),
            RegionsAbout(holes.world, a, reach) + RegionsAbout(holes.world, b, reach));
  // NoiseGrid: the samples' box grown by the reach.
  v1::NoiseGridRequest grid;
  grid.set_world_name("holes");
  grid.set_origin_x(-10);
  grid.set_origin_y(-10);
  grid.set_step(0.5);
  grid.set_width(40);
  grid.set_height(40);
  const double grown = RegionsOverlapping(RegionLayout(holes.world),
                                          {-10 - reach, -10 - reach, 9.5 + reach, 9.5 + reach})
                           .Count();
  EXPECT_EQ(static_cast<double>(RequestCost(worlds, grid, 4096)), grown);
  grid.set_world_name("dunes");
  // Without masks: the box's regions, [-10, 9.5]^2 in regions 24 wide: 2 x 2.
  EXPECT_EQ(RequestCost(worlds, grid, 4096), 4);
}

}  // namespace
}  // namespace scallop::server
