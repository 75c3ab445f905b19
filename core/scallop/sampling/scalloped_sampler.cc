// A1 and A2 implementation. Every point p keeps its available neighbourhood
//   N_p = D(p, r') - U_{q < p} D(q, r') - U_{q >= p} D(q, s)
// (s = d plus the rounding margin of spacing.h), clipped to the domain. A new
// point x gets N_x = annulus(s, r') minus the r'-disks of all earlier points,
// and x's s-disk is cut from the neighbourhoods it reaches. The union of the
// neighbourhoods is always the available area within r' of a point, so
// sampling it uniformly (A1) is dart throwing, run until no spot is left.
#include "scallop/sampling/scalloped_sampler.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "scallop/geometry/scalloped_region.h"
#include "scallop/sampling/area_sum_tree.h"
#include "scallop/sampling/cell_darts.h"
#include "scallop/sampling/point_grid.h"
#include "scallop/sampling/spacing.h"

namespace scallop {
namespace {

// Draws from one neighbourhood that fail the double-precision spacing check
// (possible only within rounding of its edge) before the neighbourhood is
// given up as a rounding-sized sliver.
constexpr int kMaxRejectedDraws = 16;

// A1 uses CellDarts for its bulk from this density (r' / d) up: see UsesCells.
constexpr double kMinCellsDensity = 1.1;

// With a stop rectangle, A1 draws from the neighbourhoods that can reach it
// alone once their area is below this share of all (see ChooseCandidate).
constexpr double kSliverShare = 0.02;

class ScallopedSampler {
 public:
  ScallopedSampler(const SamplingProblem& problem, CandidateChoice choice, A1Bulk bulk,
                   A1Reach reach, Rng& rng)
      : problem_(problem),
        choice_(choice),
        bulk_(bulk),
        anywhere_(choice == CandidateChoice::kByArea && reach == A1Reach::kAnywhere),
        in_stop_(anywhere_ && problem.stop_when_covered.has_value()),
        rng_(rng),
        outer_radius_(problem.density * problem.min_distance),
        spacing_(
            SpacingFor(problem.min_distance,
                       MaxAbsCoordinate(problem, problem.domain.torus ? 0.0 : 2 * outer_radius_))),
        d_squared_(problem.min_distance * problem.min_distance),
        grid_(problem.domain.rect, problem.domain.torus, problem.min_distance,
              problem.domain.torus ? 0.0 : 2 * problem.min_distance + spacing_),
        annulus_(ScallopedRegion::Annulus({0.0, 0.0}, spacing_, outer_radius_)) {}

  std::vector<Vec2> Run() {
    if (UsesCells()) {
      RunCells();
    } else {
      for (const Vec2& p : problem_.inert_points) AddInertPoint(p);
      for (const Vec2& p : problem_.fixed_points) AddPoint(p);
      fixed_count_ = points_.size();
      if (NeedsSeedPoint(problem_, outer_radius_)) AddPoint(SeedPoint(problem_, rng_));
    }
    for (;;) {
      // Every available spot within r' of a point lies in some neighbourhood,
      // and F1 is continuous, so once no neighbourhood that can reach the
      // stop rectangle is left, the rectangle is covered. (A plane region's
      // dart throwing keeps neighbourhoods in R alone: it ends with them.)
      if (!in_stop_ && problem_.stop_when_covered && open_near_stop_ == 0) break;
      const int32_t chosen = ChooseCandidate();
      if (chosen < 0) break;
      DrawFrom(chosen);
    }
    points_.erase(points_.begin(), points_.begin() + static_cast<std::ptrdiff_t>(fixed_count_));
    return std::move(points_);
  }

 private:
  // A1 on a plain rectangle runs its bulk with CellDarts. The plane's problems (fixed and inert
  // points, covered and stop rectangles) and tori keep the neighbourhoods throughout, and so do
  // densities below kMinCellsDensity: with r' that close to s, T is a thin band around each
  // point, most darts land beyond it, and cells were slower (0.6-0.75x at 1.05, 1.35x at 1.1).
  bool UsesCells() const {
    if (anywhere_) return true;  // kAnywhere's REQUIRES
    return choice_ == CandidateChoice::kByArea && bulk_ == A1Bulk::kCells &&
           problem_.density >= kMinCellsDensity && !problem_.domain.torus &&
           problem_.fixed_points.empty() && problem_.inert_points.empty() &&
           problem_.covered_rects.empty() && !problem_.stop_when_covered;
  }

  // The same process as AddPoint and DrawFrom, with cells for all but its last voids: the
  // points CellDarts places get no neighbourhood, and once it stops, the points within r' of
  // its open cells (which hold every spot still available and reachable) get theirs, exactly as
  // AddPoint and the cuts since would have left them. A plane region (in_stop_) files its
  // neighbours' points first, and is done if the cells find R covered; else R's last voids go
  // to the neighbourhoods of the points within r' of the open cells meeting R, clipped to R
  // (every available spot of R is within r' of a point by then: the argument of cell_darts.h),
  // and points placed from them need none (the earlier owners' disks hold what they reach).
  void RunCells() {
    std::optional<CellDarts> maybe_cells;
    if (in_stop_) {
      maybe_cells.emplace(
          problem_.domain.rect, problem_.min_distance, spacing_, outer_radius_,
          CellDarts::StoppedProblem{*problem_.stop_when_covered, problem_.covered_rects});
    } else {
      maybe_cells.emplace(problem_.domain, problem_.min_distance, spacing_, outer_radius_,
                          anywhere_ ? CellDarts::Reach::kAnywhere : CellDarts::Reach::kNearPoints);
    }
    CellDarts& cells = *maybe_cells;
    for (const Vec2& p : problem_.inert_points) {
      points_.push_back(p);
      cells.AddInertPoint(p);
    }
    for (const Vec2& p : problem_.fixed_points) {
      points_.push_back(p);
      cells.AddPoint(p);
    }
    fixed_count_ = points_.size();
    // Near points only, the set grows from one uniform point; anywhere, the first dart is one.
    std::vector<Vec2> placed;
    if (!anywhere_) {
      placed.push_back(SeedPoint(problem_, rng_));
      cells.AddPoint(placed[0]);
    }
    cells.Run(rng_, placed);
    points_.insert(points_.end(), placed.begin(), placed.end());
    for (size_t i = 0; i < points_.size(); ++i) grid_.Insert(static_cast<int32_t>(i), points_[i]);
    neighbourhoods_.resize(points_.size());
    open_near_stop_flags_.resize(points_.size(), 0);
    if (in_stop_ && cells.StopCovered()) return;
    std::vector<uint8_t> near_open(points_.size(), 0);
    cells.ForEachOpenCell(
        [&](const Rect& cell) {
          const Vec2 centre{0.5 * (cell.x0 + cell.x1), 0.5 * (cell.y0 + cell.y1)};
          grid_.ForEachNear(centre, outer_radius_ + cell.Width(), [&](int32_t index, Vec2 q) {
            if (SquaredDistance(cell, q) <= outer_radius_ * outer_radius_)
              near_open[static_cast<size_t>(index)] = 1;
          });
        },
        in_stop_);
    if (in_stop_) owners_ = near_open;
    for (size_t i = 0; i < points_.size(); ++i) {
      if (near_open[i]) BuildNeighbourhood(static_cast<int32_t>(i));
    }
  }

  // Whether the point at `index` has a neighbourhood: always, but in a plane region's dart
  // throwing only the owners RunCells chose.
  bool OwnsNeighbourhood(int32_t index) const {
    return !in_stop_ || (static_cast<size_t>(index) < owners_.size() &&
                         owners_[static_cast<size_t>(index)] != 0);
  }

  // The disk a point at `index` cuts from the neighbourhood of a later point: r' when it has a
  // neighbourhood of its own (the spots within r' of both are its), else only its s-disk.
  double EarlierDiskRadius(int32_t index) const {
    return OwnsNeighbourhood(index) ? outer_radius_ : spacing_;
  }

  // N_index as AddPoint made it and every later point's cut has left it: the annulus minus the
  // r'-disks of earlier points (EarlierDiskRadius) and the s-disks of later ones, nearest first.
  void BuildNeighbourhood(int32_t index) {
    const Vec2 x = points_[static_cast<size_t>(index)];
    ScallopedRegion& region = scratch_region_;
    region.AssignMoved(annulus_, x);
    if (in_stop_) {
      ClipTo(region, *problem_.stop_when_covered);
    } else if (!problem_.domain.torus) {
      ClipTo(region, problem_.domain.rect);
    }
    nearby_.clear();
    grid_.ForEachNear(x, 2 * outer_radius_, [&](int32_t other, Vec2 q) {
      if (other == index) return;
      const double distance_squared = SquaredDistance(q, x);
      const double radius = other < index ? EarlierDiskRadius(other) : spacing_;
      const double limit = outer_radius_ + radius;
      if (distance_squared < limit * limit) nearby_.push_back({distance_squared, other, q});
    });
    SortNearestFirst(nearby_);
    for (const Nearby& n : nearby_) {
      if (region.empty()) break;
      region.SubtractDisk(n.position, n.index < index ? EarlierDiskRadius(n.index) : spacing_);
    }
    neighbourhoods_[static_cast<size_t>(index)] = region.empty() ? ScallopedRegion() : region;
    SetNeighbourhoodArea(index);
  }

  // The index of a point with a non-empty neighbourhood, or -1 when none is left.
  int32_t ChooseCandidate() {
    if (choice_ == CandidateChoice::kByArea) {
      if (areas_.Total() <= 0.0) return -1;
      // A stopped run waits on the stop rectangle's last slivers, which a
      // choice by area reaches only after most of the domain: once they are
      // all that is left there, they go first.
      const double near_stop = near_stop_areas_.Total();
      if (!in_stop_ && near_stop > 0.0 && near_stop < kSliverShare * areas_.Total()) {
        return static_cast<int32_t>(near_stop_areas_.Pick(rng_.Uniform()));
      }
      return static_cast<int32_t>(areas_.Pick(rng_.Uniform()));
    }
    // A2: uniform over the candidates; emptied ones are dropped when met,
    // which keeps the choice uniform over the non-empty ones.
    while (!candidates_.empty()) {
      const size_t pick = rng_.Below(candidates_.size());
      const int32_t index = candidates_[pick];
      if (!neighbourhoods_[static_cast<size_t>(index)].empty()) return index;
      candidates_[pick] = candidates_.back();
      candidates_.pop_back();
    }
    return -1;
  }

  // Draws one point from N_index and adds it, or gives up a sliver.
  void DrawFrom(int32_t index) {
    ScallopedRegion& region = neighbourhoods_[static_cast<size_t>(index)];
    for (int attempt = 0; attempt < kMaxRejectedDraws; ++attempt) {
      const double u0 = rng_.Uniform(), u1 = rng_.Uniform(), u2 = rng_.Uniform();
      const Vec2 x = grid_.WrapIntoDomain(region.Sample(u0, u1, u2));
      if (Fits(x)) {
        AddPoint(x);
        return;
      }
    }
    SetNeighbourhood(index, ScallopedRegion());
  }

  // The contract's own test, in doubles, against every point near x.
  bool Fits(Vec2 x) const {
    if (!problem_.domain.torus && !problem_.domain.rect.Contains(x)) return false;
    if (InCoveredRect(problem_, x)) return false;
    bool fits = true;
    grid_.ForEachNear(x, problem_.min_distance,
                      [&](int32_t, Vec2 q) { fits = fits && SquaredDistance(q, x) >= d_squared_; });
    return fits;
  }

  void AddPoint(Vec2 x) {
    const auto index = static_cast<int32_t>(points_.size());
    points_.push_back(x);
    grid_.Insert(index, x);

    // Built in a reused scratch region (no allocation once it has grown), then copied out at
    // its final, usually small, size.
    ScallopedRegion& region = scratch_region_;
    region.AssignMoved(annulus_, x);
    if (!problem_.domain.torus) ClipTo(region, problem_.domain.rect);
    // Earlier points own what lies within r' of them; x's s-disk leaves their
    // neighbourhoods.
    nearby_.clear();
    in_reach_.clear();
    const double reach = outer_radius_ + spacing_;
    grid_.ForEachNear(x, 2 * outer_radius_, [&](int32_t other, Vec2 q) {
      if (other == index) return;
      const double distance_squared = SquaredDistance(q, x);
      if (distance_squared < 4 * outer_radius_ * outer_radius_) {
        nearby_.push_back({distance_squared, other, q});
      }
      if (distance_squared < reach * reach) {
        in_reach_.push_back({distance_squared, other, q});
        __builtin_prefetch(&neighbourhoods_[static_cast<size_t>(other)]);
      }
    });
    CutNeighbourhoods(x);
    // A plane region's dart throwing gives its last points none (RunCells).
    const bool opens = !in_stop_;
    SortNearestFirst(nearby_);
    for (const Nearby& n : nearby_) {
      if (region.empty() || !opens) break;
      region.SubtractDisk(n.position, outer_radius_);
    }
    neighbourhoods_.push_back(region.empty() || !opens ? ScallopedRegion() : region);
    open_near_stop_flags_.push_back(0);
    if (choice_ == CandidateChoice::kUniform) candidates_.push_back(index);
    SetNeighbourhoodArea(index);
  }

  // Cuts x's s-disk from the neighbourhoods of the points in in_reach_, in the grid's order. At a
  // million points each neighbourhood is a few cache misses, so all are requested before any is
  // cut (results do not depend on it).
  void CutNeighbourhoods(Vec2 x) {
    for (const Nearby& n : in_reach_) neighbourhoods_[static_cast<size_t>(n.index)].Prefetch();
    for (const Nearby& n : in_reach_) {
      ScallopedRegion& theirs = neighbourhoods_[static_cast<size_t>(n.index)];
      if (theirs.empty()) continue;
      // Images are taken near x, then moved to the point's side. On a rectangle the grid's
      // position is the point itself (same bits), so its entry in points_ need not be loaded.
      const Vec2 point = problem_.domain.torus ? points_[static_cast<size_t>(n.index)] : n.position;
      theirs.SubtractDisk(x + (point - n.position), spacing_);
      SetNeighbourhoodArea(n.index);
    }
  }

  // A point with an empty neighbourhood from the start. Added before any
  // other, so there is no earlier neighbourhood for its disk to cut.
  void AddInertPoint(Vec2 x) {
    const auto index = static_cast<int32_t>(points_.size());
    points_.push_back(x);
    grid_.Insert(index, x);
    neighbourhoods_.emplace_back();
    open_near_stop_flags_.push_back(0);
    SetNeighbourhoodArea(index);
  }

  void ClipTo(ScallopedRegion& region, const Rect& r) const {
    region.IntersectHalfPlane({1, 0}, r.x1);
    region.IntersectHalfPlane({-1, 0}, -r.x0);
    region.IntersectHalfPlane({0, 1}, r.y1);
    region.IntersectHalfPlane({0, -1}, -r.y0);
  }

  void SetNeighbourhood(int32_t index, ScallopedRegion region) {
    neighbourhoods_[static_cast<size_t>(index)] = std::move(region);
    SetNeighbourhoodArea(index);
  }

  void SetNeighbourhoodArea(int32_t index) {
    ScallopedRegion& region = neighbourhoods_[static_cast<size_t>(index)];
    // An emptied neighbourhood gives its buffers back: only the frontier holds memory.
    if (region.empty() && region.sectors().capacity() > 0) region = ScallopedRegion();
    if (choice_ == CandidateChoice::kByArea) {
      areas_.Set(static_cast<size_t>(index), region.Area());
    }
    if (problem_.stop_when_covered) {
      const auto i = static_cast<size_t>(index);
      // A1 never draws from a neighbourhood of zero area (a degenerate one
      // can remain), so only positive area keeps the run going.
      const bool open = choice_ == CandidateChoice::kByArea ? region.Area() > 0.0 : !region.empty();
      const bool open_near = open && SquaredDistance(*problem_.stop_when_covered, points_[i]) <=
                                         outer_radius_ * outer_radius_;
      open_near_stop_ += static_cast<int64_t>(open_near) - open_near_stop_flags_[i];
      open_near_stop_flags_[i] = open_near;
      if (choice_ == CandidateChoice::kByArea)
        near_stop_areas_.Set(i, open_near ? region.Area() : 0.0);
    }
  }

  struct Nearby {
    double distance_squared;
    int32_t index;
    Vec2 position;
  };

  // Nearest first: their disks cover the most of an annulus, so a region shrinks (or empties)
  // early and most later disks miss it cheaply. Ties are broken by index so the order is a pure
  // function of the points.
  static void SortNearestFirst(std::vector<Nearby>& nearby) {
    std::sort(nearby.begin(), nearby.end(), [](const Nearby& a, const Nearby& b) {
      return a.distance_squared != b.distance_squared ? a.distance_squared < b.distance_squared
                                                      : a.index < b.index;
    });
  }

  const SamplingProblem& problem_;
  const CandidateChoice choice_;
  const A1Bulk bulk_;
  const bool anywhere_;          // A1Reach::kAnywhere
  const bool in_stop_;           // ... on a plane region: CellDarts::Reach::kInStop
  std::vector<uint8_t> owners_;  // in_stop_: the points that have a neighbourhood
  Rng& rng_;
  const double outer_radius_;  // r'
  const double spacing_;       // s: d plus the rounding margin
  const double d_squared_;
  PointGrid grid_;
  std::vector<Vec2> points_;
  size_t fixed_count_ = 0;
  std::vector<ScallopedRegion> neighbourhoods_;
  std::vector<Nearby> nearby_;       // scratch of AddPoint
  std::vector<Nearby> in_reach_;     // scratch of AddPoint: points whose neighbourhood x may cut
  ScallopedRegion scratch_region_;   // scratch of AddPoint
  const ScallopedRegion annulus_;    // every new point's annulus s..r', made once, moved to each
  AreaSumTree areas_;                // A1
  std::vector<int32_t> candidates_;  // A2
  // With a stop rectangle: how many non-empty neighbourhoods belong to points
  // within r' of it (the only ones that can reach it), and which.
  int64_t open_near_stop_ = 0;
  std::vector<uint8_t> open_near_stop_flags_;
  AreaSumTree near_stop_areas_;  // A1: the areas of those neighbourhoods
};

}  // namespace

std::vector<Vec2> SampleScalloped(const SamplingProblem& problem, CandidateChoice choice, Rng& rng,
                                  A1Bulk bulk, A1Reach reach) {
  return ScallopedSampler(problem, choice, bulk, reach, rng).Run();
}

}  // namespace scallop
