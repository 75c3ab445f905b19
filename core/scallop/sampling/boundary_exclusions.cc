// BoundaryExclusions: the disks filed in cells of the largest radius, with a DiskBins table for
// each pair of radii (a circle's and a disk's) whose ratio has one, and the second intersection
// rule for the arcs the tables leave.
#include "scallop/sampling/boundary_exclusions.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <utility>

#include "scallop/sampling/boundary_arcs.h"
#include "scallop/sampling/spacing.h"

namespace scallop {
namespace {

// The table for a disk of radius `disk` (cut at disk_cut) seen from a circle of radius `circle`
// (cut at circle_cut): that of the given ratio, when the cut radii's ratio lies within its slack
// (far from the origin the margins are absolute, and a small radius's ratio moves more).
const DiskBins* TableFor(double disk, double disk_cut, double circle, double circle_cut) {
  const double ratio = disk / circle;
  const double slack = 0.5 * DiskBins::kRatioSlack * ratio;
  return std::abs(disk_cut / circle_cut - ratio) <= slack ? DiskBins::ForRatio(ratio) : nullptr;
}

// The set bits of each byte (std::popcount is a library call without -mpopcnt).
constexpr std::array<uint8_t, 256> kOnesIn = [] {
  std::array<uint8_t, 256> ones{};
  for (int b = 1; b < 256; ++b) ones[b] = static_cast<uint8_t>(ones[b / 2] + b % 2);
  return ones;
}();

}  // namespace

void BoundaryExclusions::Reset(std::span<const ExclusionDisk> disks, double min_distance,
                               double spacing, double max_abs_coordinate) {
  spacing_ = spacing;
  radii_.clear();
  largest_cut_ = 0.0;
  from_point_.clear();
  disks_.clear();
  StartSearch(0.0);
  std::vector<Disk>& given = given_;
  given.clear();
  given.reserve(disks.size());
  for (const ExclusionDisk& disk : disks) {
    if (!(disk.radius > 0.0)) continue;
    // Disks come layer by layer, so the last radius is nearly always the one.
    auto radius = static_cast<uint32_t>(radii_.size());
    if (!radii_.empty() && radii_.back().given == disk.radius) {
      radius = radius - 1;
    } else {
      for (uint32_t r = 0; r < radii_.size(); ++r) {
        if (radii_[r].given == disk.radius) radius = r;
      }
    }
    if (radius == radii_.size()) {
      const double cut = SpacingFor(disk.radius, max_abs_coordinate);
      radii_.push_back({disk.radius,
                        cut,
                        disk.radius * disk.radius,
                        TableFor(disk.radius, cut, min_distance, spacing),
                        {},
                        nullptr});
      largest_cut_ = std::max(largest_cut_, cut);
    }
    given.push_back({disk.centre, radii_[radius].cut, radius});
  }
  if (given.empty()) return;
  for (Radius& circle : radii_) {
    circle.point_from_here = TableFor(min_distance, spacing, circle.given, circle.cut);
    for (const Radius& disk : radii_) {
      circle.from_disk.push_back(TableFor(disk.given, disk.cut, circle.given, circle.cut));
    }
    from_point_.push_back(circle.from_point);
  }

  // Filed by cell (a counting sort, stable), so that a query reads consecutive disks.
  Vec2 low = given.front().centre, high = low;
  for (const Disk& disk : given) {
    low = {std::min(low.x, disk.centre.x), std::min(low.y, disk.centre.y)};
    high = {std::max(high.x, disk.centre.x), std::max(high.y, disk.centre.y)};
  }
  origin_ = low;
  inverse_cell_ = 1.0 / largest_cut_;
  columns_ = static_cast<int64_t>((high.x - low.x) * inverse_cell_) + 1;
  rows_ = static_cast<int64_t>((high.y - low.y) * inverse_cell_) + 1;
  const auto column_row_of = [&](Vec2 p) {
    return std::pair{
        std::min(static_cast<int64_t>((p.x - origin_.x) * inverse_cell_), columns_ - 1),
        std::min(static_cast<int64_t>((p.y - origin_.y) * inverse_cell_), rows_ - 1)};
  };
  const auto cell_of = [&](Vec2 p) {
    const auto [column, row] = column_row_of(p);
    return static_cast<size_t>(row * columns_ + column);
  };
  cell_start_.assign(static_cast<size_t>(columns_ * rows_) + 1, 0);
  uint32_t most = 0;  // disks in the fullest cell
  for (const Disk& disk : given) most = std::max(most, ++cell_start_[cell_of(disk.centre) + 1]);
  for (size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  disks_.resize(given.size());
  std::vector<uint32_t>& filled = cell_filled_;
  filled.assign(cell_start_.begin(), cell_start_.end() - 1);
  for (const Disk& disk : given) disks_[filled[cell_of(disk.centre)]++] = disk;
  arcs_.reserve(disks_.size());
  if (near_.size() < disks_.size() + 1) near_.resize(disks_.size() + 1);

  occupancy_.clear();
  filed_before_.clear();
  if (most > 1) return;
  occupancy_stride_ = (columns_ + 7) / 8 + 8;
  occupancy_.assign(static_cast<size_t>((rows_ + 7) * occupancy_stride_), 0);
  for (const Disk& disk : given) {
    const auto [column, row] = column_row_of(disk.centre);
    occupancy_[static_cast<size_t>(row * occupancy_stride_ + column / 8)] |=
        static_cast<uint8_t>(1u << (column % 8));
  }
  if (cell_start_.size() <= kCountedCells) return;
  // Disks are filed by cell, row-major, one a cell at most: a cell's disk is numbered by the
  // occupied cells before it.
  filed_before_.resize(static_cast<size_t>(rows_ * occupancy_stride_));
  uint32_t filed = 0;
  for (size_t b = 0; b < filed_before_.size(); ++b) {
    filed_before_[b] = filed;
    filed += kOnesIn[occupancy_[b]];
  }
}

bool BoundaryExclusions::AddExactArc(Vec2 offset, double disk_radius) {
  KeyArc arc{0, 0};
  const DiskCover cover = CoveredArcOfCircle(offset, circle_, disk_radius, arc);
  if (cover == DiskCover::kWhole) return false;
  if (cover == DiskCover::kNone) return true;
  const ArcBins bins = BinsOf(arc);
  covered_ |= bins.covered;
  arcs_.push_back({bins, offset, disk_radius, static_cast<int32_t>(exact_arcs_.size())});
  exact_arcs_.push_back(arc);
  return true;
}

void BoundaryExclusions::StartSearch(double circle) {
  arcs_.clear();
  covered_ = 0;
  exact_arcs_.clear();
  near_count_ = 0;
  circle_ = circle;
}

bool BoundaryExclusions::AddDisksNear(const Vec2& centre, const DiskBins* const* tables,
                                      size_t skip) {
  if (disks_.empty()) return true;
  const double circle = circle_;
  // Cells clamped to the grid: every centre lies in it, so the clamped range still holds each
  // centre within reach. Clamped first, truncation is floor (std::floor is a libm call here).
  const double reach = circle + largest_cut_, scale = 16.0 / circle;
  const auto index = [&](double offset, int64_t count) {
    return static_cast<int64_t>(
        std::clamp(offset * inverse_cell_, 0.0, static_cast<double>(count - 1)));
  };
  const int64_t c0 = index(centre.x - reach - origin_.x, columns_);
  const int64_t c1 = index(centre.x + reach - origin_.x, columns_);
  const int64_t r0 = index(centre.y - reach - origin_.y, rows_);
  const int64_t r1 = index(centre.y + reach - origin_.y, rows_);
  if (!occupancy_.empty() && c1 - c0 < 8 && r1 - r0 < 8) {
    GatherByOccupancy(centre, c0, c1, r0, r1);
  } else {
    GatherByRows(centre, c0, c1, r0, r1);
  }
  // Then their arcs.
  bool whole = false;
  for (size_t n = 0; n < near_count_; ++n) {
    const uint32_t k = near_[n];
    if (k == skip) continue;
    const Disk& disk = disks_[k];
    whole = whole || !AddArc(disk.centre - centre, scale, disk.cut, tables[disk.radius]);
  }
  return !whole;
}

void BoundaryExclusions::GatherByOccupancy(const Vec2& centre, int64_t c0, int64_t c1, int64_t r0,
                                           int64_t r1) {
  const double circle = circle_;
  // Bit 8 k + j: the cell of row r0 + k, column c0 + j, holds a disk; ascending bits are
  // ascending numbers. Always 8 rows, those past r1 masked off: a fixed count, no branch.
  const uint64_t row_mask = (uint64_t{2} << (c1 - c0)) - 1;
  uint64_t occupied = 0;
  for (int64_t k = 0; k < 8; ++k) {
    uint64_t word;  // little-endian: byte b of a row holds its columns 8 b to 8 b + 7
    std::memcpy(&word, &occupancy_[static_cast<size_t>((r0 + k) * occupancy_stride_ + c0 / 8)], 8);
    const uint64_t in_window = -static_cast<uint64_t>(k <= r1 - r0);
    occupied |= ((word >> (c0 % 8)) & row_mask & in_window) << (8 * k);
  }
  // Each filed without a branch on whether it is near.
  while (occupied != 0) {
    const int bit = std::countr_zero(occupied);
    occupied &= occupied - 1;
    const int64_t column = c0 + (bit & 7), row = r0 + (bit >> 3);
    uint32_t k;
    if (filed_before_.empty()) {  // the same for every search of a run: predicted
      k = cell_start_[static_cast<size_t>(row * columns_ + column)];
    } else {
      const auto byte = static_cast<size_t>(row * occupancy_stride_ + column / 8);
      k = filed_before_[byte] + kOnesIn[occupancy_[byte] & ((1u << (column % 8)) - 1)];
    }
    const Disk& disk = disks_[k];
    const double meets = circle + disk.cut;
    near_[near_count_] = k;
    near_count_ += SquaredLength(disk.centre - centre) < meets * meets;
  }
}

void BoundaryExclusions::GatherByRows(const Vec2& centre, int64_t c0, int64_t c1, int64_t r0,
                                      int64_t r1) {
  const double circle = circle_;
  // The disks near, filed without a branch each (whether one is near cannot be predicted)...
  const auto top = static_cast<uint32_t>(disks_.size() - 1);
  for (int64_t row = r0; row <= r1; ++row) {
    const uint32_t first = cell_start_[static_cast<size_t>(row * columns_ + c0)];
    const uint32_t last = cell_start_[static_cast<size_t>(row * columns_ + c1) + 1];
    // ... the first two in the row's cells without a branch on how many there are (in a
    // forest's 250k query a search reads 3.8 disks in 5.1 rows, so a loop's end was a coin
    // toss in every row)...
    for (uint32_t k = first; k < first + 2; ++k) {
      const Disk& disk = disks_[std::min(k, top)];
      const double meets = circle + disk.cut;
      near_[near_count_] = k;
      near_count_ += static_cast<size_t>(k < last) &
                     static_cast<size_t>(SquaredLength(disk.centre - centre) < meets * meets);
    }
    // ... and any more.
    for (uint32_t k = first + 2; k < last; ++k) {
      const Disk& disk = disks_[k];
      const double meets = circle + disk.cut;
      near_[near_count_] = k;
      near_count_ += SquaredLength(disk.centre - centre) < meets * meets;
    }
  }
}

void BoundaryExclusions::Cut(AvailableBoundary& boundary) const {
  // The bins the ranges meet; the arcs that meet none of them change nothing.
  const uint64_t met = boundary.BinsMet();
  const uint64_t covered = covered_;
  if ((met & ~covered) == 0) {
    boundary.Clear();  // every bin the ranges meet lies inside one arc
    return;
  }
  // Runs of covered bins lie inside arcs, closed: cut as they are.
  for (uint64_t runs = covered & met; runs != 0;) {
    const uint64_t run = runs & ~(runs + (runs & -runs));
    runs &= ~run;
    boundary.SubtractArc(std::countr_zero(run) / kBinsPerKey,
                         (64 - std::countl_zero(run)) / kBinsPerKey);
  }
  const uint64_t left = met & ~covered;
  for (const DiskArc& disk : arcs_) {
    if ((disk.bins.reached & left) == 0 || boundary.empty()) continue;
    KeyArc arc{0, 0};
    const DiskCover cover =
        disk.exact >= 0 ? (arc = exact_arcs_[static_cast<size_t>(disk.exact)], DiskCover::kArc)
                        : CoveredArcOfCircle(disk.offset, circle_, disk.disk_radius, arc);
    if (cover == DiskCover::kWhole) boundary.Clear();
    if (cover == DiskCover::kArc) boundary.SubtractArc(arc.from_key, arc.to_key);
  }
}

bool BoundaryExclusions::GatherAroundDisk(size_t k, std::span<const Vec2> points) {
  const Disk& disk = disks_[k];
  const Radius& circle = radii_[disk.radius];
  StartSearch(circle.cut);
  // The points' arcs first: they cover nearly every disk's circle (by their bins alone), and
  // then the other disks are not searched.
  const double meets = circle.cut + spacing_, scale = 16.0 / circle.cut;
  if (const DiskBins* table = circle.point_from_here) {
    // By the table alone first, keeping nothing: 9 circles in 10 are covered whole, and those
    // need neither the arcs kept nor the points after the one that completes the cover.
    uint64_t covered = 0;
    for (const Vec2& point : points) {
      const Vec2 offset = point - disk.centre;
      if (SquaredLength(offset) >= meets * meets) continue;
      covered |= table->Of(offset, scale).covered;
      if (covered == ~uint64_t{0}) return false;
    }
  }
  for (const Vec2& point : points) {
    const Vec2 offset = point - disk.centre;
    if (SquaredLength(offset) >= meets * meets) continue;
    if (!AddArc(offset, scale, spacing_, circle.point_from_here)) return false;
  }
  return GatheredCoveredBins() != ~uint64_t{0};
}

void BoundaryExclusions::CutGatheredDisk(size_t k, AvailableBoundary& boundary) {
  const Disk& disk = disks_[k];
  if ((boundary.BinsMet() & ~GatheredCoveredBins()) == 0 ||
      !AddDisksNear(disk.centre, radii_[disk.radius].from_disk.data(), k)) {
    boundary.Clear();
    return;
  }
  Cut(boundary);
}

bool BoundaryExclusions::Excludes(Vec2 x) const {
  bool inside = false;
  for (size_t n = 0; n < near_count_; ++n) {
    const Disk& disk = disks_[near_[n]];
    inside = inside || SquaredDistance(x, disk.centre) < radii_[disk.radius].squared;
  }
  return inside;
}

bool BoundaryExclusions::AnyExcludes(Vec2 x) const {
  bool inside = false;
  for (const Disk& disk : disks_) {
    inside = inside || SquaredDistance(x, disk.centre) < radii_[disk.radius].squared;
  }
  return inside;
}

}  // namespace scallop
