// Bins of arcs: from an arc's keys, and by table from a neighbour's offset.
#include "scallop/sampling/arc_bins.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <numbers>

namespace scallop {

ArcBins BinsOf(const KeyArc& arc) {
  // Keys are not negative, so truncation is floor; a key of exactly 4 is in bin 63.
  const int first = std::min(static_cast<int>(arc.from_key * kBinsPerKey), 63);
  const int last = std::min(static_cast<int>(arc.to_key * kBinsPerKey), 63);
  const uint64_t from_first = ~uint64_t{0} << first;
  const uint64_t up_to_last = (uint64_t{2} << last) - 1;  // 2 << 63 is 0: all ones
  // An arc that passes key 0 reaches the bins of either mask, one that does
  // not those of both.
  const uint64_t passes_zero = -static_cast<uint64_t>(arc.from_key > arc.to_key);
  const uint64_t reached = (from_first & up_to_last) | ((from_first | up_to_last) & passes_zero);
  // The first and last bins reached may be covered whole too; leaving them
  // out only costs an exact cut.
  const uint64_t after_first = from_first << 1, before_last = up_to_last >> 1;
  const uint64_t covered =
      (after_first & before_last) | ((after_first | before_last) & passes_zero);
  return {covered, reached};
}

const NeighbourBins::Cells& NeighbourBins::Table() {
  static const Cells table = Build();
  return table;
}

NeighbourBins::Cells NeighbourBins::Build() {
  Cells cells;
  BuildArcBinCells(1.0, 1e-7, kCells / 2, cells.data());
  return cells;
}

DiskBins::DiskBins(double ratio)
    : half_cells_(static_cast<int>(std::ceil(16 * (1 + ratio * (1 + kRatioSlack))))),
      side_(2 * half_cells_ + 1),
      cells_(static_cast<size_t>(side_ * side_)) {
  // The margin covers a disk radius up to kRatioSlack off: g moves by ratio^2 kRatioSlack at
  // most, half the added term.
  BuildArcBinCells(ratio, 1e-7 + ratio * ratio * 0x1.0p-13, half_cells_, cells_.data());
}

const DiskBins* DiskBins::ForRatio(double ratio) {
  if (!(ratio > 0.0 && ratio <= kMaxRatio)) return nullptr;
  // A cache of a pure function: which tables exist never changes what a sampler computes.
  static std::mutex mutex;
  static std::map<uint64_t, std::unique_ptr<const DiskBins>> tables;
  std::lock_guard lock(mutex);
  const auto found = tables.find(std::bit_cast<uint64_t>(ratio));
  if (found != tables.end()) return found->second.get();
  if (tables.size() >= static_cast<size_t>(kMaxTables)) return nullptr;
  std::unique_ptr<const DiskBins> table(new DiskBins(ratio));
  return tables.emplace(std::bit_cast<uint64_t>(ratio), std::move(table)).first->second.get();
}

void BuildArcBinCells(double ratio, double margin, int half_cells, ArcBins* cells) {
  // In units of the circle's radius: direction u (unit) is on the arc of a disk of radius
  // `ratio` at offset o when |u - o| <= ratio, that is when
  // g(u, o) = u.o - (|o|^2 + 1 - ratio^2) / 2 >= 0 (u.o - |o|^2 / 2 for equal radii: 1 - 1 is 0,
  // so the table of NeighbourBins keeps its bits). Bins claimed within `margin` of the arc's
  // end are not.
  constexpr double kGrow = 1e-7;  // cells grown by this: o / s is computed as o * (16 / s)
  constexpr int kSamples = 17;    // directions across a bin, for `reached`
  const double constant = 1 - ratio * ratio;
  struct Bin {
    Vec2 ends[2];            // unit directions at keys k / 16 and (k + 1) / 16
    Vec2 middle;             // the unit direction halfway between, by angle
    double angles[2];        // radians of the ends, angles[0] in [0, 2 pi), angles[1] above it
    double half_angle;       // half the bin's angle, radians, rounded up
    Vec2 samples[kSamples];  // from ends[0] on, `step` radians apart
    double step;
  };
  std::array<Bin, 64> bins;
  for (int k = 0; k < 64; ++k) {
    Bin& bin = bins[k];
    for (int e = 0; e < 2; ++e) {
      // Building the table is not generating: libm is fine here, within the margins.
      const Vec2 v = DirectionAtKey((k + e) / kBinsPerKey);
      const double length = Length(v);
      bin.ends[e] = {v.x / length, v.y / length};
      bin.angles[e] = std::atan2(v.y, v.x);
    }
    if (bin.angles[0] < 0) bin.angles[0] += 2 * std::numbers::pi;
    while (bin.angles[1] <= bin.angles[0]) bin.angles[1] += 2 * std::numbers::pi;
    const double middle = (bin.angles[0] + bin.angles[1]) / 2;
    bin.middle = {std::cos(middle), std::sin(middle)};
    bin.half_angle = (bin.angles[1] - bin.angles[0]) / 2 * (1 + 1e-9) + 1e-12;
    bin.step = 2 * bin.half_angle / (kSamples - 1);
    for (int i = 0; i < kSamples; ++i) {
      bin.samples[i] = {std::cos(bin.angles[0] + i * bin.step),
                        std::sin(bin.angles[0] + i * bin.step)};
    }
  }
  auto g = [constant](Vec2 u, Vec2 o) { return Dot(u, o) - (SquaredLength(o) + constant) / 2; };
  // Whether the bin holds the direction opposite to o (to within a hair, counted as held): there
  // u.o is least, -|o|. With a disk no larger than the circle g < 0 there at both ends anyway;
  // with a larger one both ends may be covered while the middle is not.
  auto holds_opposite = [](const Bin& bin, Vec2 o) {
    double opposite = std::atan2(-o.y, -o.x);
    while (opposite < bin.angles[0] - 1e-9) opposite += 2 * std::numbers::pi;
    return opposite <= bin.angles[1] + 1e-9;
  };
  const int side = 2 * half_cells + 1;  // one more: an offset within rounding of the edge
  const double half = half_cells / 16.0;
  const double width = 1.0 / 16;
  for (int row = 0; row < side; ++row) {
    for (int column = 0; column < side; ++column) {
      const double x0 = -half + column * width - kGrow, x1 = -half + (column + 1) * width + kGrow;
      const double y0 = -half + row * width - kGrow, y1 = -half + (row + 1) * width + kGrow;
      const Vec2 corners[4] = {{x0, y0}, {x1, y0}, {x0, y1}, {x1, y1}};
      const Vec2 centre = {(x0 + x1) / 2, (y0 + y1) / 2};
      const double half_diagonal = std::hypot(x1 - x0, y1 - y0) / 2;
      const double longest = Length(centre) + half_diagonal;  // |o| in the cell, at most
      ArcBins& out = cells[row * side + column];
      out = {0, 0};
      for (int k = 0; k < 64; ++k) {
        const Bin& bin = bins[k];
        // Covered: g >= margin over the whole cell and bin. min over the bin's directions of
        // g is concave in o (a least of functions concave in o), so its least value over the
        // cell is at a corner; for a corner, over the bin's directions (narrower than pi) it
        // is at an end, or at the direction of -o if the bin holds it.
        bool covered = true;
        for (const Vec2& corner : corners) {
          for (const Vec2& end : bin.ends) covered = covered && g(end, corner) >= margin;
          if (ratio > 1 && covered && holds_opposite(bin, corner)) {
            covered = -Length(corner) - (SquaredLength(corner) + constant) / 2 >= margin;
          }
        }
        // Reached: g >= -margin somewhere, for all we can tell. As
        // g(u, o) = (ratio^2 - |o - u|^2) / 2, that is where some direction of the bin comes
        // within sqrt(ratio^2 + 2 margin) of the cell. A quick bound from the centres first
        // (|dg / d angle| <= |o|, |dg / do| = |u - o| <= 1 + |o|), then, for the bins it lets
        // through, the distance at kSamples directions across the bin, less half a step (the
        // distance changes by no more than the chord between them).
        bool reached = covered;
        if (!covered &&
            g(bin.middle, centre) + longest * bin.half_angle + (1 + longest) * half_diagonal >=
                -margin) {
          const double within = std::sqrt(ratio * ratio + 2 * margin) + bin.step / 2;
          for (int i = 0; i < kSamples && !reached; ++i) {
            const Vec2 u = bin.samples[i];
            const double dx = std::max({x0 - u.x, 0.0, u.x - x1});
            const double dy = std::max({y0 - u.y, 0.0, u.y - y1});
            reached = dx * dx + dy * dy <= within * within;
          }
        }
        out.covered |= uint64_t{covered} << k;
        out.reached |= uint64_t{reached} << k;
      }
    }
  }
}

}  // namespace scallop
