// Bins of arcs: from an arc's keys, and by table from a neighbour's offset.
#include "scallop/sampling/arc_bins.h"

#include <algorithm>
#include <cmath>
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
  // In units of s: direction u (unit) is on the arc of offset o when
  // |u - o| <= 1, that is when g(u, o) = u.o - |o|^2 / 2 >= 0.
  constexpr double kMargin = 1e-7;  // in g: bins claimed within it of the arc's end are not
  constexpr double kGrow = 1e-7;    // cells grown by this: o / s is computed as o * (16 / s)
  constexpr int kSamples = 17;      // directions across a bin, for `reached`
  struct Bin {
    Vec2 ends[2];            // unit directions at keys k / 16 and (k + 1) / 16
    Vec2 middle;             // the unit direction halfway between, by angle
    double half_angle;       // half the bin's angle, radians, rounded up
    Vec2 samples[kSamples];  // from ends[0] on, `step` radians apart
    double step;
  };
  std::array<Bin, 64> bins;
  for (int k = 0; k < 64; ++k) {
    Bin& bin = bins[k];
    double angles[2];
    for (int e = 0; e < 2; ++e) {
      // Building the table is not generating: libm is fine here, within the margins.
      const Vec2 v = DirectionAtKey((k + e) / kBinsPerKey);
      const double length = Length(v);
      bin.ends[e] = {v.x / length, v.y / length};
      angles[e] = std::atan2(v.y, v.x);
    }
    if (angles[0] < 0) angles[0] += 2 * std::numbers::pi;
    while (angles[1] <= angles[0]) angles[1] += 2 * std::numbers::pi;
    const double middle = (angles[0] + angles[1]) / 2;
    bin.middle = {std::cos(middle), std::sin(middle)};
    bin.half_angle = (angles[1] - angles[0]) / 2 * (1 + 1e-9) + 1e-12;
    bin.step = 2 * bin.half_angle / (kSamples - 1);
    for (int i = 0; i < kSamples; ++i) {
      bin.samples[i] = {std::cos(angles[0] + i * bin.step), std::sin(angles[0] + i * bin.step)};
    }
  }
  auto g = [](Vec2 u, Vec2 o) { return Dot(u, o) - SquaredLength(o) / 2; };
  Cells cells;
  const double width = 4.0 / kCells;
  for (int row = 0; row < kSide; ++row) {
    for (int column = 0; column < kSide; ++column) {
      const double x0 = -2 + column * width - kGrow, x1 = -2 + (column + 1) * width + kGrow;
      const double y0 = -2 + row * width - kGrow, y1 = -2 + (row + 1) * width + kGrow;
      const Vec2 corners[4] = {{x0, y0}, {x1, y0}, {x0, y1}, {x1, y1}};
      const Vec2 centre = {(x0 + x1) / 2, (y0 + y1) / 2};
      const double half_diagonal = std::hypot(x1 - x0, y1 - y0) / 2;
      const double longest = Length(centre) + half_diagonal;  // |o| in the cell, at most
      ArcBins& out = cells[row * kSide + column];
      out = {0, 0};
      for (int k = 0; k < 64; ++k) {
        const Bin& bin = bins[k];
        // Covered: g >= margin over the whole cell and bin. g is concave in
        // o, so its least value over the cell is at a corner; over the
        // bin's directions (narrower than pi) at an end, unless the bin
        // holds the direction of -o, where g < 0 at both ends anyway.
        bool covered = true;
        for (const Vec2& corner : corners) {
          for (const Vec2& end : bin.ends) covered = covered && g(end, corner) >= kMargin;
        }
        // Reached: g >= -margin somewhere, for all we can tell. As
        // g(u, o) = (1 - |o - u|^2) / 2, that is where some direction of the
        // bin comes within sqrt(1 + 2 margin) of the cell. A quick bound
        // from the centres first (|dg / d angle| <= |o|, |dg / do| = |u - o|
        // <= 1 + |o|), then, for the bins it lets through, the distance at
        // kSamples directions across the bin, less half a step (the distance
        // changes by no more than the chord between them).
        bool reached = covered;
        if (!covered &&
            g(bin.middle, centre) + longest * bin.half_angle + (1 + longest) * half_diagonal >=
                -kMargin) {
          const double within = std::sqrt(1 + 2 * kMargin) + bin.step / 2;
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
  return cells;
}

}  // namespace scallop
