// The load generator's tile placement: the cold lattice and the warm square.
#include "bench/load_tile_plan.h"

#include <cmath>

namespace scallop::load {
namespace {

// Room kept free between two cold tiles of neighbouring cells: each query's
// regions reach at most 48 d past its edge (the edge's region plus a halo of
// two 16 d regions), so 128 d keeps the two sets of regions apart.
constexpr double kColdGap = 128;

}  // namespace

uint64_t SplitMix64(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

double UnitInterval(uint64_t bits) { return static_cast<double>(bits >> 11) * 0x1.0p-53; }

TilePlan::TilePlan(const TilePlanOptions& options) : options_(options) {
  // Whole multiples of the cell side, so that a run's corner is exact.
  const double corners = std::ldexp(1.0, 31) / kColdCellSide;
  const auto corner = [&](uint64_t stream) {
    const double unit = UnitInterval(SplitMix64(SplitMix64(options_.run_seed) ^ stream));
    return std::floor((2 * unit - 1) * corners) * kColdCellSide;
  };
  lattice_x0_ = corner(1);
  lattice_y0_ = corner(2);
}

Rect TilePlan::Tile(int64_t k) const {
  const double side = options_.tile_side;
  const uint64_t bits = SplitMix64(options_.run_seed * 0x100000001b3ULL + static_cast<uint64_t>(k));
  // Two independent 32-bit fractions of one draw place the tile.
  const double u = static_cast<double>(bits >> 32) * 0x1.0p-32;
  const double v = static_cast<double>(bits & 0xffffffffULL) * 0x1.0p-32;
  double x0 = 0;
  double y0 = 0;
  if (options_.mode == LoadMode::kCold) {
    const double room = kColdCellSide - side - kColdGap;
    x0 = lattice_x0_ + static_cast<double>(k % kColdLatticeColumns) * kColdCellSide + u * room;
    y0 = lattice_y0_ + static_cast<double>(k / kColdLatticeColumns) * kColdCellSide + v * room;
  } else {
    const double room = options_.warm_side - side;
    x0 = u * room;
    y0 = v * room;
  }
  return {x0, y0, x0 + side, y0 + side};
}

std::vector<Rect> TilePlan::WarmUpTiles() const {
  std::vector<Rect> tiles;
  if (options_.mode == LoadMode::kCold) return tiles;
  const double side = options_.tile_side;
  for (double y = 0; y < options_.warm_side; y += side) {
    for (double x = 0; x < options_.warm_side; x += side)
      tiles.push_back({x, y, x + side, y + side});
  }
  return tiles;
}

}  // namespace scallop::load
