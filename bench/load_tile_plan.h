// Where the load generator's requests go: the k-th tile of a run as a pure
// function of (run seed, k), so streams share one request counter and a run
// is repeatable. Cold tiles are far apart in a fresh world; warm tiles stay
// inside a small square that a warm-up has already cached.
#pragma once

#include <cstdint>
#include <vector>

#include "scallop/geometry/rect.h"

namespace scallop::load {

enum class LoadMode { kCold, kWarm };

struct TilePlanOptions {
  LoadMode mode = LoadMode::kWarm;
  double tile_side = 64;   // in world units (the benchmark's worlds have d = 1)
  double warm_side = 256;  // side of the warm square [0, warm_side)^2
  uint64_t run_seed = 1;   // places the cold lattice and the warm tiles
};

// Cold tiles sit one per cell of a lattice whose cells are kColdCellSide
// apart, at a random offset inside their cell. A cold query generates its
// regions plus a halo of at most 2 regions (32 d) on each side, so tiles
// 1024 d apart never share a region: every cold request generates all of its
// regions. The lattice (1024 x 1024 cells) starts at a random corner within
// +-2^31 d, well inside the 2^32 d precision range.
inline constexpr double kColdCellSide = 1024;
inline constexpr int64_t kColdLatticeColumns = 1024;
inline constexpr int64_t kMaxColdTiles = kColdLatticeColumns * kColdLatticeColumns;

class TilePlan {
 public:
  explicit TilePlan(const TilePlanOptions& options);

  // The k-th measured tile, k < kMaxColdTiles in cold mode. Cheap, thread-safe.
  Rect Tile(int64_t k) const;

  // Warm mode: the aligned tiles that cover the warm square, to query once
  // before measuring. Empty in cold mode (nothing may be cached there).
  std::vector<Rect> WarmUpTiles() const;

  const TilePlanOptions& options() const { return options_; }

 private:
  TilePlanOptions options_;
  double lattice_x0_ = 0;
  double lattice_y0_ = 0;
};

// SplitMix64 (Steele, Lea and Flood 2014) of x: a counter-based generator, so
// tile k does not depend on which stream asked for it.
uint64_t SplitMix64(uint64_t x);

// A double in [0, 1) from the top 53 bits of a 64-bit value.
double UnitInterval(uint64_t bits);

}  // namespace scallop::load
