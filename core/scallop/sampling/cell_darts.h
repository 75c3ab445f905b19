// CellDarts: the bulk of A1, run with grid cells instead of neighbourhoods.
//
// A1 places each next point uniformly over T, the spots it may draw from: with Reach::kAnywhere
// every available spot of the domain (at least s, the spacing, from every point: dart throwing
// itself), with Reach::kNearPoints only those within r' of a point (the paper's A1, whose
// restriction packs denser below r' = 2 d). A dart drawn uniformly from any union of cells that
// holds T, and kept only when it lands in T, follows the same law, and needs no neighbourhood.
// The cells are the point grid's (side just under d / sqrt 2, so a point covers its own cell).
// With kAnywhere every cell is open from the start; with kNearPoints a cell opens once it comes
// within r' of a point. A cell closes when a point lands in it or when the s-disks around it
// provably cover it (every edge covered, every crossing of two circles inside it covered by a
// third, with a margin far above rounding). A cell that darts keep missing is split in four and
// its children tested the same way (the refinement of Ebeida et al. 2011), down to kFinestLevel.
//
// Run stops once only finest-level cells are left open: they hold the last, thin voids, where
// darts almost never land. The caller then finishes with exact neighbourhoods of radius r',
// built only for the points within r' of an open cell (ForEachOpenCell); no other point's
// neighbourhood can be non-empty, since T lies inside the open cells. With kAnywhere (used at
// r' = 2 d) that finish draws from all of T too: a spot of the domain farther than r' from every
// point would be the centre of an available disk of radius r' - s (about d), whose part in the
// domain (a quarter of it at worst, in a corner) holds a whole level-1 cell; no dart in that
// cell can miss, so it is never split or closed, and Run would not have stopped.
//
// On a torus (kAnywhere only) a point near an edge also files its images across that edge, so
// that coverage and the spacing test see distances with wrap-around.
//
// A plane region (Reach::kInStop, a StoppedProblem) is dart throwing in its rectangle R with a
// rate that tapers beyond it: a dart at distance t outside R is kept with probability
// Taper(t), from 1 at R's edge to 0 at kTaperReach ((1 - t / reach)^6), so what the run leaves past
// R when it stops is a set thinning out smoothly, never a front frozen at a wall. Inside R the law
// is dart throwing's. The problem adds fixed and inert points from the neighbours (filed in a grid
// grown by 2 r' + s) and rectangles closed to the run (their cells closed at the start, darts there
// missing); every cell within kTaperReach of R opens at the start, the others never. Run stops once
// no open cell meets R: R is covered. Once the cells meeting R hold less than kSliverShare of the
// open area, darts go to them alone (the run would otherwise wait on R's last voids while the band
// fills).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "scallop/geometry/domain.h"
#include "scallop/geometry/rect.h"
#include "scallop/geometry/vec2.h"
#include "scallop/random/rng.h"
#include "scallop/sampling/boundary_grid.h"

namespace scallop {

class CellDarts {
 public:
  static constexpr int kFinestLevel = 8;      // cells 2^-8 of the grid's side
  static constexpr int kFailuresToSplit = 6;  // darts a cell misses before it is split or retested

  // Which spots T holds: see the top of this file.
  enum class Reach { kNearPoints, kAnywhere, kInStop };

  // kInStop: how far past R darts may land (in units of min_distance), and when R's cells go
  // first. Taper's reach stays inside the plane's 6.5 d margin.
  static constexpr double kTaperReach = 6.0;
  static constexpr double kSliverShare = 0.02;

  // What a plane region adds (Reach::kInStop): see the top of this file.
  struct StoppedProblem {
    Rect stop;                     // R, inside the domain by at least kTaperReach d
    std::span<const Rect> closed;  // no new point may land in them (a covered rectangle)
  };

  // The probability a dart at `outside` (its distance past R, in units of the taper's reach)
  // is kept: (1 - outside)^6, 0.33 at 1 d, 0.016 at 3 d, 2e-5 at 5 d. A fast fall matters: the
  // band's fill goes by the log of its rate (dart throwing saturates in any time), and a gentle
  // taper (smoothstep) left it 95% full to 5.5 d, a wall again. Only *, so the same bits
  // everywhere.
  static double Taper(double outside) {
    if (!(outside > 0.0)) return 1.0;
    if (outside >= 1.0) return 0.0;
    const double left = 1.0 - outside, squared = left * left;
    return squared * squared * squared;
  }

  // REQUIRES: a non-empty rectangle, 0 < min_distance <= spacing < outer_radius <= 2 spacing;
  // a torus only with kAnywhere, its sides at least 4 spacing.
  CellDarts(const Domain& domain, double min_distance, double spacing, double outer_radius,
            Reach reach = Reach::kNearPoints);
  CellDarts(const Rect& domain, double min_distance, double spacing, double outer_radius)
      : CellDarts(Domain{domain, false}, min_distance, spacing, outer_radius) {}
  // Reach::kInStop on a rectangle, outer_radius = 2 spacing. REQUIRES: as above.
  CellDarts(const Rect& domain, double min_distance, double spacing, double outer_radius,
            const StoppedProblem& stopped);

  // A point that only constrains (a plane region's inert point): filed for the spacing and
  // coverage tests, no cell changes. REQUIRES: within 2 r' + s of the domain.
  void AddInertPoint(Vec2 p) { grid_.Insert(-1, p); }

  // Adds a point placed by the caller (the seed, a plane region's fixed points): it closes,
  // covers and opens cells as a dart does. REQUIRES: p in the domain (kInStop: within
  // 2 r' + s of it), at least `spacing` from every point added.
  // Cost: O((r' / d)^2) cells (O(1) with kAnywhere), a coverage test for each whose corners
  // it completes.
  void AddPoint(Vec2 p);

  // Throws darts until no cell coarser than the finest level is open, or `placed` holds
  // `max_points` (tests stop early to check the cells mid-run), appending each kept dart to
  // `placed` (after adding it). Draws from `rng` only. Cost, measured on a 1118 d square at
  // r' = 2 d: 8.4 darts and 6.5 coverage tests a point (a test is cubic in the handful of disks
  // near a cell), and it placed 99.93% of the points; O(N) expected.
  // kInStop: Run also returns once only finest cells meet R (the caller's neighbourhoods finish
  // R), or none (R is covered: StopCovered).
  void Run(Rng& rng, std::vector<Vec2>& placed, size_t max_points = SIZE_MAX);

  // kInStop: true when no open cell meets R, so R is covered.
  bool StopCovered() const { return OpenArea(kMeetsStop, kFinestLevel + 1) == 0.0; }

  // Calls visit(cell) for every open cell: together they hold every spot of T. kInStop: only
  // those that meet R when `meeting_stop_only`.
  template <typename Visit>
  void ForEachOpenCell(Visit&& visit, bool meeting_stop_only = false) const {
    for (int group = 0; group < (meeting_stop_only ? 1 : kGroups); ++group) {
      for (const int32_t id : open_[group]) visit(TopCell(id));
      for (int level = 1; level <= kFinestLevel; ++level) {
        for (const SubCell& cell : sub_[static_cast<size_t>(level)][group]) {
          visit(Rect{cell.x, cell.y, cell.x + side_[level], cell.y + side_[level]});
        }
      }
    }
  }

 private:
  enum State : uint8_t { kUntouched, kOpen, kClosed, kSplit };
  // Open cells are kept in two groups: kInStop's cells that meet R, and the others (every cell
  // in the other modes), so that R's last voids can be drawn from alone.
  enum Group { kMeetsStop = 0, kOther = 1 };
  static constexpr int kGroups = 2;
  struct SubCell {
    double x, y;  // lower-left corner
    int32_t failures;
  };

  Rect TopCell(int32_t id) const;
  // The part of `cell` in the (closed) domain: the only part that can hold spots of T.
  Rect InDomain(const Rect& cell) const;
  int32_t TopCellId(Vec2 p) const;
  // What a disk centred at p (a point, or on a torus one of its images) does to the cells
  // within reach_ of it: opens the untouched ones within r', covers corners within s.
  void UpdateCellsAround(Vec2 p);
  void Open(int32_t id);
  void Close(int32_t id);
  Group GroupOf(const Rect& cell) const;
  Group TopGroup(int32_t id) const { return GroupOf(InDomain(TopCell(id))); }
  void PushSubCell(int level, double x, double y);
  void RemoveSubCell(int level, int group, size_t index);
  size_t OpenCount(int level, int group) const {
    return level == 0 ? open_[group].size() : sub_[static_cast<size_t>(level)][group].size();
  }
  // The open area of `group`'s cells of the levels below `levels`.
  double OpenArea(int group, int levels) const;
  bool InClosedRect(Vec2 p) const;
  bool WhollyInClosedRect(const Rect& cell) const;
  // Bits 0-3: which corners of the cell `disk` covers with room to spare.
  uint8_t CornersCovered(const Rect& cell, Vec2 disk) const;
  // The points whose s-disk may reach `cell`, into disks_.
  void GatherDisks(const Rect& cell);
  // True when `disks` cover `cell` with room to spare (never wrongly). REQUIRES: every disk
  // that reaches the cell is among them.
  bool Covered(const Rect& cell, std::span<const Vec2> disks) const;
  bool Covered(const Rect& cell) const { return Covered(cell, disks_); }
  // After a dart missed T in the open cell at `index` of `level`'s list: counts the miss, and
  // every kFailuresToSplit misses splits the cell (at the finest level, retests it).
  void Missed(int level, int group, size_t index);

  Rect domain_;
  bool torus_;
  bool has_stop_ = false;  // kInStop
  Rect stop_{};
  std::vector<Rect> closed_;
  double taper_per_distance_ = 0.0;  // 1 / (kTaperReach min_distance)
  Reach reach_kind_;
  double reach_;  // how far a point's disk can change a cell: r', or s with kAnywhere
  double spacing_;
  double spacing_squared_;
  double covered_squared_;  // a disk "surely" holds spots this close to its centre
  double outer_radius_;
  double outer_squared_;
  double cell_size_;
  int64_t columns_, rows_;
  BoundaryGrid grid_;
  std::vector<State> state_;      // per top cell
  std::vector<uint8_t> corners_;  // per top cell: CornersCovered of all disks so far
  std::vector<uint8_t> failures_;
  std::vector<int32_t> where_;                           // per open top cell: index in its list
  std::vector<int32_t> open_[kGroups];                   // open top cells
  std::vector<SubCell> sub_[kFinestLevel + 1][kGroups];  // open cells of finer levels ([0] unused)
  double side_[kFinestLevel + 1];
  double area_[kFinestLevel + 1];
  std::vector<Vec2> disks_;        // scratch
  std::vector<Vec2> child_disks_;  // scratch
  std::vector<Vec2> nearby_;       // scratch
};

}  // namespace scallop
