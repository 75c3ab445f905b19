// CellDarts implementation.
#include "scallop/sampling/cell_darts.h"

#include <algorithm>
#include <cmath>

namespace scallop {
namespace {

// A coverage claim needs the spot this much inside a disk (relative to s^2): far above the
// rounding of the tests below (a few ulps), far below anything a sampler could notice.
constexpr double kCoverageMargin = 1e-9;

}  // namespace

CellDarts::CellDarts(const Domain& domain, double min_distance, double spacing, double outer_radius,
                     Reach reach)
    : domain_(domain.rect),
      torus_(domain.torus),
      reach_kind_(reach),
      reach_(reach == Reach::kNearPoints ? outer_radius : spacing),
      spacing_(spacing),
      spacing_squared_(spacing * spacing),
      covered_squared_(spacing * spacing * (1.0 - kCoverageMargin)),
      outer_radius_(outer_radius),
      outer_squared_(outer_radius * outer_radius),
      // PointGrid's cells (BoundaryGrid's are a millionth smaller): a point
      // covers its own cell, whose diagonal is just under d.
      cell_size_(min_distance / std::sqrt(2.0) * (1.0 - 1e-9)),
      columns_(static_cast<int64_t>(std::floor(domain.rect.Width() / cell_size_)) + 1),
      rows_(static_cast<int64_t>(std::floor(domain.rect.Height() / cell_size_)) + 1),
      // On a torus the images filed across the edges lie within s of the rectangle; a plane
      // region's fixed and inert points within 2 r' (and 1%) of it.
      grid_(domain.rect, min_distance,
            domain.torus              ? spacing
            : reach == Reach::kInStop ? 2 * outer_radius + spacing
                                      : 0.0) {
  const auto cells = static_cast<size_t>(columns_ * rows_);
  state_.assign(cells, kUntouched);
  corners_.assign(cells, 0);
  failures_.assign(cells, 0);
  where_.assign(cells, -1);
  for (int level = 0; level <= kFinestLevel; ++level) {
    side_[level] = std::ldexp(cell_size_, -level);
    area_[level] = side_[level] * side_[level];
  }
  if (reach_kind_ == Reach::kAnywhere) {
    for (int32_t id = 0; id < static_cast<int32_t>(cells); ++id) {
      const Rect cell = InDomain(TopCell(id));
      if (cell.x0 < cell.x1 && cell.y0 < cell.y1) {
        Open(id);
      } else {
        state_[static_cast<size_t>(id)] = kClosed;  // starts on the domain's far edge: no spot
      }
    }
  }
}

CellDarts::CellDarts(const Rect& domain, double min_distance, double spacing, double outer_radius,
                     const StoppedProblem& stopped)
    : CellDarts(Domain{domain, false}, min_distance, spacing, outer_radius, Reach::kInStop) {
  has_stop_ = true;
  stop_ = stopped.stop;
  closed_.assign(stopped.closed.begin(), stopped.closed.end());
  taper_per_distance_ = 1.0 / (kTaperReach * min_distance);
  // Every cell that may hold a spot of T (within the taper's reach of R, outside the closed
  // rectangles) is open from the start; points only cover.
  const Rect reach = Grown(stop_, kTaperReach * min_distance);
  for (int32_t id = 0; id < static_cast<int32_t>(state_.size()); ++id) {
    const Rect cell = InDomain(TopCell(id));
    const bool meets_reach =
        cell.x0 < reach.x1 && reach.x0 < cell.x1 && cell.y0 < reach.y1 && reach.y0 < cell.y1;
    if (cell.x0 < cell.x1 && cell.y0 < cell.y1 && meets_reach && !WhollyInClosedRect(cell)) {
      Open(id);
    } else {
      state_[static_cast<size_t>(id)] = kClosed;
    }
  }
}

CellDarts::Group CellDarts::GroupOf(const Rect& cell) const {
  const bool meets = has_stop_ && cell.x0 <= stop_.x1 && stop_.x0 <= cell.x1 &&
                     cell.y0 <= stop_.y1 && stop_.y0 <= cell.y1;
  return meets ? kMeetsStop : kOther;
}

void CellDarts::PushSubCell(int level, double x, double y) {
  const Group group = GroupOf(InDomain({x, y, x + side_[level], y + side_[level]}));
  sub_[static_cast<size_t>(level)][group].push_back({x, y, 0});
}

void CellDarts::RemoveSubCell(int level, int group, size_t index) {
  std::vector<SubCell>& cells = sub_[static_cast<size_t>(level)][group];
  cells[index] = cells.back();
  cells.pop_back();
}

double CellDarts::OpenArea(int group, int levels) const {
  double area = 0.0;
  for (int level = 0; level < levels; ++level) {
    area += static_cast<double>(OpenCount(level, group)) * area_[level];
  }
  return area;
}

bool CellDarts::InClosedRect(Vec2 p) const {
  for (const Rect& r : closed_) {
    if (r.Contains(p)) return true;
  }
  return false;
}

bool CellDarts::WhollyInClosedRect(const Rect& cell) const {
  // Strictly below the high edges: the rectangles are half-open.
  for (const Rect& r : closed_) {
    if (r.x0 <= cell.x0 && cell.x1 < r.x1 && r.y0 <= cell.y0 && cell.y1 < r.y1) return true;
  }
  return false;
}

Rect CellDarts::InDomain(const Rect& cell) const {
  return {std::max(cell.x0, domain_.x0), std::max(cell.y0, domain_.y0),
          std::min(cell.x1, domain_.x1), std::min(cell.y1, domain_.y1)};
}

Rect CellDarts::TopCell(int32_t id) const {
  const double x = domain_.x0 + static_cast<double>(id % columns_) * cell_size_;
  const double y = domain_.y0 + static_cast<double>(id / columns_) * cell_size_;
  return {x, y, x + cell_size_, y + cell_size_};
}

int32_t CellDarts::TopCellId(Vec2 p) const {
  const int64_t column =
      std::clamp<int64_t>(static_cast<int64_t>((p.x - domain_.x0) / cell_size_), 0, columns_ - 1);
  const int64_t row =
      std::clamp<int64_t>(static_cast<int64_t>((p.y - domain_.y0) / cell_size_), 0, rows_ - 1);
  return static_cast<int32_t>(row * columns_ + column);
}

void CellDarts::Open(int32_t id) {
  const auto i = static_cast<size_t>(id);
  state_[i] = kOpen;
  std::vector<int32_t>& open = open_[TopGroup(id)];
  where_[i] = static_cast<int32_t>(open.size());
  open.push_back(id);
}

void CellDarts::Close(int32_t id) {
  const auto i = static_cast<size_t>(id);
  if (state_[i] == kOpen) {
    std::vector<int32_t>& open = open_[TopGroup(id)];
    const int32_t last = open.back();
    open[static_cast<size_t>(where_[i])] = last;
    where_[static_cast<size_t>(last)] = where_[i];
    open.pop_back();
  }
  state_[i] = kClosed;
}

uint8_t CellDarts::CornersCovered(const Rect& cell, Vec2 disk) const {
  uint8_t bits = 0;
  for (int corner = 0; corner < 4; ++corner) {
    const Vec2 spot{(corner & 1) ? cell.x1 : cell.x0, (corner & 2) ? cell.y1 : cell.y0};
    if (SquaredDistance(spot, disk) < covered_squared_) bits |= static_cast<uint8_t>(1 << corner);
  }
  return bits;
}

void CellDarts::GatherDisks(const Rect& cell) {
  const Vec2 centre{0.5 * (cell.x0 + cell.x1), 0.5 * (cell.y0 + cell.y1)};
  // s beyond the half-diagonal (with 1% to spare for rounding): every disk that reaches a
  // corner of the cell has its centre this close to the cell's centre.
  const double reach = spacing_ + 0.5 * std::sqrt(2.0) * cell.Width() * 1.01;
  const size_t count = grid_.GatherNear(centre, reach, reach * reach, -1, nearby_);
  disks_.clear();
  for (size_t k = 0; k < count; ++k) {
    if (SquaredDistance(cell, nearby_[k]) < spacing_squared_) disks_.push_back(nearby_[k]);
  }
}

bool CellDarts::Covered(const Rect& cell, std::span<const Vec2> disks) const {
  // A spot of the cell outside every disk would lie in a region whose boundary has a corner
  // that is either a spot of the cell's edges or a crossing of two circles inside the cell
  // (a region outside all disks cannot be bounded by whole circles). So: every edge covered,
  // and every crossing inside the closed cell covered by a third disk. Ties count as uncovered.
  const double radius_squared = covered_squared_;
  for (int edge = 0; edge < 4; ++edge) {
    const bool horizontal = edge < 2;
    const double fixed = edge == 0 ? cell.y0 : edge == 1 ? cell.y1 : edge == 2 ? cell.x0 : cell.x1;
    const double low = horizontal ? cell.x0 : cell.y0, high = horizontal ? cell.x1 : cell.y1;
    // The edge's intervals inside each disk, sorted by start (a handful: insertion sort).
    double starts[64], ends[64];
    int count = 0;
    for (const Vec2& disk : disks) {
      const double offset = horizontal ? disk.y - fixed : disk.x - fixed;
      const double half_squared = radius_squared - offset * offset;
      if (!(half_squared > 0.0) || count == 64) continue;
      const double half = std::sqrt(half_squared), middle = horizontal ? disk.x : disk.y;
      int j = count++;
      for (; j > 0 && starts[j - 1] > middle - half; --j) {
        starts[j] = starts[j - 1];
        ends[j] = ends[j - 1];
      }
      starts[j] = middle - half;
      ends[j] = middle + half;
    }
    double reached = low;
    for (int i = 0; i < count && reached <= high; ++i) {
      if (!(starts[i] < reached)) return false;
      reached = std::max(reached, ends[i]);
    }
    if (!(reached > high)) return false;
  }
  const size_t n = disks.size();
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = i + 1; j < n; ++j) {
      const Vec2 delta = disks[j] - disks[i];
      const double distance_squared = SquaredLength(delta);
      if (!(distance_squared < 4.0 * radius_squared) || distance_squared == 0.0) continue;
      const double distance = std::sqrt(distance_squared);
      const double half_chord = std::sqrt(radius_squared - 0.25 * distance_squared);
      const Vec2 middle = disks[i] + 0.5 * delta;
      const Vec2 across = (half_chord / distance) * Vec2{-delta.y, delta.x};
      for (const Vec2 crossing : {middle - across, middle + across}) {
        if (crossing.x < cell.x0 || crossing.x > cell.x1 || crossing.y < cell.y0 ||
            crossing.y > cell.y1) {
          continue;
        }
        bool covered = false;
        for (size_t k = 0; k < n && !covered; ++k) {
          covered = k != i && k != j && SquaredDistance(crossing, disks[k]) < radius_squared;
        }
        if (!covered) return false;
      }
    }
  }
  return true;
}

void CellDarts::AddPoint(Vec2 p) {
  grid_.Insert(-1, p);
  // A point in a split cell leaves its children open: darts there miss and retire them. (A
  // plane region's fixed point may lie outside the domain: no cell of its own.)
  if (domain_.x0 <= p.x && p.x <= domain_.x1 && domain_.y0 <= p.y && p.y <= domain_.y1) {
    const int32_t own = TopCellId(p);
    if (state_[static_cast<size_t>(own)] != kSplit) Close(own);
  }
  UpdateCellsAround(p);
  if (!torus_) return;
  // The images whose s-disk reaches into the rectangle (those across an edge and, near a
  // corner, across both).
  const double width = domain_.Width(), height = domain_.Height();
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      if (dx == 0 && dy == 0) continue;
      const Vec2 image{p.x + dx * width, p.y + dy * height};
      if (SquaredDistance(domain_, image) < spacing_squared_) {
        grid_.Insert(-1, image);
        UpdateCellsAround(image);
      }
    }
  }
}

void CellDarts::UpdateCellsAround(Vec2 p) {
  // Columns and rows of cells within reach_ of p (which may lie off the rectangle: an image),
  // one more each way, which covers rounding and truncation towards zero (floor is a libm
  // call without SSE4.1); each cell is measured below.
  const double per_cell = 1.0 / cell_size_;
  const auto first = [&](double v, double origin) {
    return static_cast<int64_t>((v - reach_ - origin) * per_cell) - 1;
  };
  const auto last = [&](double v, double origin) {
    return static_cast<int64_t>((v + reach_ - origin) * per_cell) + 1;
  };
  for (int64_t row = std::max<int64_t>(first(p.y, domain_.y0), 0);
       row <= std::min<int64_t>(last(p.y, domain_.y0), rows_ - 1); ++row) {
    for (int64_t column = std::max<int64_t>(first(p.x, domain_.x0), 0);
         column <= std::min<int64_t>(last(p.x, domain_.x0), columns_ - 1); ++column) {
      const auto id = static_cast<int32_t>(row * columns_ + column);
      const State state = state_[static_cast<size_t>(id)];
      if (state == kClosed || state == kSplit) continue;
      // Only the part in the domain can hold spots of T; a cell that starts on the domain's
      // far edge has none.
      const Rect cell = InDomain(TopCell(id));
      if (!(cell.x0 < cell.x1 && cell.y0 < cell.y1)) continue;
      const double distance_squared = SquaredDistance(cell, p);
      if (state == kUntouched) {
        if (distance_squared > outer_squared_) continue;
        // Untouched, the cell was beyond r' (> s) of every earlier point: p alone can cover
        // corners of it, and if it covers all four it covers the cell (disks are convex).
        Open(id);
        const uint8_t corners = CornersCovered(cell, p);
        corners_[static_cast<size_t>(id)] = corners;
        if (corners == 15) Close(id);
        continue;
      }
      if (!(distance_squared < spacing_squared_)) continue;
      const auto corners =
          static_cast<uint8_t>(corners_[static_cast<size_t>(id)] | CornersCovered(cell, p));
      corners_[static_cast<size_t>(id)] = corners;
      if (corners == 15) {
        GatherDisks(cell);
        if (Covered(cell)) Close(id);
      }
    }
  }
}

void CellDarts::Missed(int level, int group, size_t index) {
  Rect cell;
  if (level == 0) {
    const int32_t id = open_[group][index];
    if (++failures_[static_cast<size_t>(id)] < kFailuresToSplit) return;
    cell = TopCell(id);
    Close(id);
    state_[static_cast<size_t>(id)] = kSplit;
    GatherDisks(cell);
  } else {
    std::vector<SubCell>& cells = sub_[static_cast<size_t>(level)][group];
    SubCell& sub = cells[index];
    if (++sub.failures % kFailuresToSplit != 0) return;
    cell = {sub.x, sub.y, sub.x + side_[level], sub.y + side_[level]};
    GatherDisks(cell);
    if (level == kFinestLevel) {
      // The finest cells are not split: retested now and then, else left to the caller.
      if (Covered(InDomain(cell))) RemoveSubCell(level, group, index);
      return;
    }
    RemoveSubCell(level, group, index);
  }
  const double half = 0.5 * (cell.x1 - cell.x0);
  for (int quarter = 0; quarter < 4; ++quarter) {
    const double x = cell.x0 + ((quarter & 1) ? half : 0.0);
    const double y = cell.y0 + ((quarter & 2) ? half : 0.0);
    if (x >= domain_.x1 || y >= domain_.y1) continue;  // wholly outside the domain
    const Rect child = InDomain({x, y, x + half, y + half});
    if (has_stop_ && WhollyInClosedRect(child)) continue;
    // Only the disks that reach the child: the crossing test is cubic in their number.
    child_disks_.clear();
    for (const Vec2& disk : disks_) {
      if (SquaredDistance(child, disk) < spacing_squared_) child_disks_.push_back(disk);
    }
    if (!Covered(child, child_disks_)) PushSubCell(level + 1, x, y);
  }
}

void CellDarts::Run(Rng& rng, std::vector<Vec2>& placed, size_t max_points) {
  // A safety valve: should darts ever stall, the caller's exact neighbourhoods take over early.
  constexpr int64_t kMaxMissesInARow = 1 << 20;
  int64_t misses_in_a_row = 0;
  while (placed.size() < max_points) {
    // Which groups darts go to: both, or (kInStop) R's cells alone once they hold little of the
    // open area. kInStop hands over when only finest cells meet R.
    int first_group = 0, end_group = kGroups;
    if (has_stop_) {
      if (OpenArea(kMeetsStop, kFinestLevel) == 0.0) return;
      const double near = OpenArea(kMeetsStop, kFinestLevel + 1);
      if (near < kSliverShare * (near + OpenArea(kOther, kFinestLevel + 1))) end_group = 1;
    } else {
      double coarse = 0.0;
      for (int group = 0; group < kGroups; ++group) coarse += OpenArea(group, kFinestLevel);
      if (!(coarse > 0.0)) return;
    }
    double total = 0.0;
    for (int group = first_group; group < end_group; ++group) {
      total += OpenArea(group, kFinestLevel + 1);
    }
    // A level and group by open area, then a cell of it uniformly, then a spot of the cell.
    double target = rng.Uniform() * total;
    int level = 0, group = first_group;
    for (;; ++level) {
      bool found = false;
      for (group = first_group; group < end_group; ++group) {
        const double area = static_cast<double>(OpenCount(level, group)) * area_[level];
        if (target < area) {
          found = true;
          break;
        }
        target -= area;
      }
      if (found || level == kFinestLevel) break;
    }
    if (group == end_group) group = end_group - 1;  // rounding in the running subtraction
    const size_t count = OpenCount(level, group);
    if (count == 0) continue;  // rounding in the running subtraction: draw again
    const size_t index = rng.Below(count);
    Rect cell;
    if (level == 0) {
      cell = TopCell(open_[group][index]);
    } else {
      const SubCell& sub = sub_[static_cast<size_t>(level)][group][index];
      cell = {sub.x, sub.y, sub.x + side_[level], sub.y + side_[level]};
    }
    const double u = rng.Uniform();
    const Vec2 dart{cell.x0 + u * side_[level], cell.y0 + rng.Uniform() * side_[level]};
    // Outside the domain (or in a closed rectangle) is a miss too: a cell mostly outside it is
    // then split, and its children wholly outside are dropped.
    const bool inside = domain_.Contains(dart) && !(has_stop_ && InClosedRect(dart));
    // In T: no point within s (most darts stop here), and with kNearPoints one within r'.
    // GatherNear keeps exactly the points closer than its limit, so the counts answer both.
    const bool available =
        inside && grid_.GatherNear(dart, spacing_, spacing_squared_, -1, nearby_) == 0;
    // With kNearPoints a dart beyond r' of every point counts as a miss too: splitting then
    // isolates such spots, which the caller's neighbourhoods finish like any other.
    if (!available || (reach_kind_ == Reach::kNearPoints &&
                       grid_.GatherNear(dart, outer_radius_, outer_squared_, -1, nearby_) == 0)) {
      Missed(level, group, index);
      if (++misses_in_a_row == kMaxMissesInARow) return;
      continue;
    }
    misses_in_a_row = 0;
    // kInStop past R: an available spot, kept at the taper's rate (a dart not kept is no miss).
    if (has_stop_) {
      const double outside = std::sqrt(SquaredDistance(stop_, dart)) * taper_per_distance_;
      if (outside > 0.0 && !(rng.Uniform() < Taper(outside))) continue;
    }
    if (level > 0) RemoveSubCell(level, group, index);
    AddPoint(dart);
    placed.push_back(dart);
  }
}

}  // namespace scallop
