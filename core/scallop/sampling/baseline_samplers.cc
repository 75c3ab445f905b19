// Baseline samplers. Written for clarity over speed, except where a baseline
// would otherwise not finish at the sizes the benchmarks compare.
#include "scallop/sampling/baseline_samplers.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "scallop/sampling/point_grid.h"

namespace scallop {
namespace {

// The points kept so far, with the grid that finds their neighbours.
class SpacedSet {
 public:
  explicit SpacedSet(const SamplingProblem& problem)
      : domain_(problem.domain),
        d_squared_(problem.min_distance * problem.min_distance),
        grid_(problem.domain.rect, problem.domain.torus, problem.min_distance, 0.0) {}

  // True when p is at least d from every kept point (double precision).
  bool Fits(Vec2 p) const {
    bool fits = true;
    grid_.ForEachNear(p, std::sqrt(d_squared_), [&](int32_t, Vec2 q) {
      if (SquaredDistance(p, q) < d_squared_) fits = false;
    });
    return fits;
  }

  void Add(Vec2 p) {
    grid_.Insert(static_cast<int32_t>(points_.size()), p);
    points_.push_back(p);
  }

  // Distance from p to the nearest kept point, or infinity when none is
  // within `limit` (a search radius that bounds the work).
  double NearestWithin(Vec2 p, double limit) const {
    double best_squared = std::numeric_limits<double>::infinity();
    grid_.ForEachNear(p, limit, [&](int32_t, Vec2 q) {
      best_squared = std::min(best_squared, SquaredDistance(p, q));
    });
    return best_squared <= limit * limit ? std::sqrt(best_squared)
                                         : std::numeric_limits<double>::infinity();
  }

  Vec2 UniformPoint(Rng& rng) const {
    const Rect& r = domain_.rect;
    const double x = rng.Uniform(r.x0, r.x1);
    return {x, rng.Uniform(r.y0, r.y1)};
  }

  const PointGrid& grid() const { return grid_; }
  std::vector<Vec2>& points() { return points_; }
  const Domain& domain() const { return domain_; }

 private:
  Domain domain_;
  double d_squared_;
  PointGrid grid_;
  std::vector<Vec2> points_;
};

}  // namespace

std::vector<Vec2> SampleDartThrowing(const SamplingProblem& problem, int64_t failure_limit,
                                     Rng& rng) {
  SpacedSet set(problem);
  for (int64_t misses = 0; misses < failure_limit;) {
    const Vec2 p = set.UniformPoint(rng);
    if (set.Fits(p)) {
      set.Add(p);
      misses = 0;
    } else {
      ++misses;
    }
  }
  return std::move(set.points());
}

std::vector<Vec2> SampleExhaustiveDartThrowing(const SamplingProblem& problem, Rng& rng) {
  const Rect& rect = problem.domain.rect;
  const double d = problem.min_distance;
  SpacedSet set(problem);

  // Level-0 cells: squares of side about d / 2 tiling the rectangle.
  struct Cell {
    double x, y;  // lower-left corner
  };
  const auto columns = static_cast<int64_t>(std::ceil(rect.Width() / (0.5 * d)));
  const auto rows = static_cast<int64_t>(std::ceil(rect.Height() / (0.5 * d)));
  double cell_width = rect.Width() / static_cast<double>(columns);
  double cell_height = rect.Height() / static_cast<double>(rows);
  std::vector<Cell> cells;
  cells.reserve(static_cast<size_t>(columns * rows));
  for (int64_t r = 0; r < rows; ++r) {
    for (int64_t c = 0; c < columns; ++c) {
      cells.push_back({rect.x0 + static_cast<double>(c) * cell_width,
                       rect.y0 + static_cast<double>(r) * cell_height});
    }
  }

  // A cell is covered when one disk holds all four corners (disks are convex).
  auto covered = [&](const Cell& cell) {
    const Vec2 corners[4] = {{cell.x, cell.y},
                             {cell.x + cell_width, cell.y},
                             {cell.x, cell.y + cell_height},
                             {cell.x + cell_width, cell.y + cell_height}};
    bool any = false;
    set.grid().ForEachNear(corners[0], 2 * d, [&](int32_t, Vec2 q) {
      if (any) return;
      bool all = true;
      for (const Vec2& corner : corners) {
        all = all && SquaredDistance(set.grid().NearestImage(corner, q), corner) < d * d;
      }
      any = all;
    });
    return any;
  };

  // Below this cell size the uncovered spot left is a rounding artefact.
  const double smallest_cell = d * 1e-9;
  std::vector<Cell> next;
  while (!cells.empty()) {
    // Throw as many darts as there are cells, dropping covered cells as we go.
    const size_t darts = cells.size();
    for (size_t k = 0; k < darts && !cells.empty(); ++k) {
      const size_t pick = rng.Below(cells.size());
      const Cell cell = cells[pick];
      const Vec2 p = set.grid().WrapIntoDomain(
          {cell.x + rng.Uniform() * cell_width, cell.y + rng.Uniform() * cell_height});
      if ((problem.domain.torus || rect.Contains(p)) && set.Fits(p)) set.Add(p);
      if (covered(cell)) {
        cells[pick] = cells.back();
        cells.pop_back();
      }
    }
    if (cells.empty() || cell_width < smallest_cell) break;
    // Split the survivors in four and keep the uncovered children, in a
    // canonical order so that the result depends only on the seed.
    std::sort(cells.begin(), cells.end(),
              [](const Cell& a, const Cell& b) { return a.y != b.y ? a.y < b.y : a.x < b.x; });
    next.clear();
    cell_width *= 0.5;
    cell_height *= 0.5;
    for (const Cell& cell : cells) {
      for (int child = 0; child < 4; ++child) {
        const Cell c{cell.x + (child & 1) * cell_width, cell.y + (child >> 1) * cell_height};
        if (!covered(c)) next.push_back(c);
      }
    }
    cells.swap(next);
  }
  return std::move(set.points());
}

std::vector<Vec2> SampleBestCandidate(const SamplingProblem& problem, int factor, Rng& rng) {
  SpacedSet set(problem);
  const Rect& rect = problem.domain.rect;
  const double d = problem.min_distance;
  // Every point of the domain is within its diagonal of every other.
  const double diagonal = std::hypot(rect.Width(), rect.Height());
  // While the set is small a scan of all points beats a grid search whose
  // radius spans most of the domain.
  constexpr size_t kScanAllBelow = 256;
  auto nearest_within = [&](Vec2 c, double radius) {
    if (set.points().size() >= kScanAllBelow) return set.NearestWithin(c, radius);
    double best_squared = std::numeric_limits<double>::infinity();
    for (const Vec2& q : set.points()) {
      best_squared = std::min(best_squared, SquaredDistance(set.grid().NearestImage(c, q), c));
    }
    return best_squared <= radius * radius ? std::sqrt(best_squared)
                                           : std::numeric_limits<double>::infinity();
  };

  set.Add(set.UniformPoint(rng));
  for (;;) {
    const size_t candidates = static_cast<size_t>(factor) * set.points().size();
    Vec2 best{};
    double best_distance = -1.0;
    for (size_t k = 0; k < candidates; ++k) {
      const Vec2 c = set.UniformPoint(rng);
      // A point within best_distance means c cannot beat the best (ties keep the first).
      if (best_distance >= 0 && std::isfinite(nearest_within(c, best_distance))) continue;
      double search = 2.0 * std::max(best_distance, d);
      double distance = nearest_within(c, search);
      while (std::isinf(distance) && search < diagonal) {
        search = std::min(2.0 * search, diagonal);
        distance = nearest_within(c, search);
      }
      best_distance = std::isinf(distance) ? diagonal : distance;
      best = c;
    }
    if (best_distance < d || !set.Fits(best)) break;
    set.Add(best);
  }
  return std::move(set.points());
}

std::vector<Vec2> SampleBridson(const SamplingProblem& problem, int attempts, Rng& rng) {
  SpacedSet set(problem);
  const double d = problem.min_distance;
  std::vector<int32_t> active;
  set.Add(set.UniformPoint(rng));
  active.push_back(0);
  while (!active.empty()) {
    const size_t pick = rng.Below(active.size());
    const Vec2 p = set.points()[static_cast<size_t>(active[pick])];
    bool placed = false;
    for (int attempt = 0; attempt < attempts && !placed; ++attempt) {
      // Uniform by area over the annulus d..2d.
      const double radius = std::sqrt(d * d + rng.Uniform() * 3.0 * d * d);
      const Vec2 x = set.grid().WrapIntoDomain(p + radius * UnitAt(rng.Uniform() * 6.283185307179586));
      if ((set.domain().torus || set.domain().rect.Contains(x)) && set.Fits(x)) {
        active.push_back(static_cast<int32_t>(set.points().size()));
        set.Add(x);
        placed = true;
      }
    }
    if (!placed) {
      active[pick] = active.back();
      active.pop_back();
    }
  }
  return std::move(set.points());
}

}  // namespace scallop
