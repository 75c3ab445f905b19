// ScallopedRegion set operations. Every operation is one generic pass (Apply): per sector, split
// the angular range at the critical angles where the ordering of the bounding distances can
// change, decide at each piece's mid-angle which radial intervals survive and which curve bounds
// them, then merge neighbouring pieces with identical curves.
#include "scallop/geometry/scalloped_region.h"
#include "scallop/base/deterministic_math.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace scallop {
namespace {

constexpr double kPi = std::numbers::pi;

// What an operation keeps along one ray: the distances in [lower, upper], with the curve that
// bounds each end (nullptr: the apex for `lower`, infinity for `upper`).
struct KeptInterval {
  const RadialCurve* lower = nullptr;
  double lower_distance = 0.0;
  const RadialCurve* upper = nullptr;
  double upper_distance = 0.0;
};

Vec2 Perpendicular(Vec2 v) { return {-v.y, v.x}; }
// sqrt of the squared length: std::hypot (Length) guards against overflow we cannot meet here and
// costs several times more.
double FastLength(Vec2 v) { return std::sqrt(SquaredLength(v)); }
Vec2 Normalized(Vec2 v) { return (1.0 / FastLength(v)) * v; }

// Whether the closed wedge from unit direction `begin` counter-clockwise to `end` (at most pi
// wide) contains direction v. Exact sign tests, no angles.
bool InWedge(Vec2 begin, Vec2 end, Vec2 v) {
  return Cross(begin, v) >= 0.0 && Cross(v, end) >= 0.0;
}

// Whether two closed wedges, each less than pi wide (by the sign of the cross product of its
// ends), may overlap: one contains the other's start or the other contains this one's start.
// Wedges that are (to rounding) pi wide or wider answer true: the test is only a shortcut.
bool WedgesMayOverlap(Vec2 begin_a, Vec2 end_a, Vec2 begin_b, Vec2 end_b) {
  if (!(Cross(begin_a, end_a) > 0.0) || !(Cross(begin_b, end_b) > 0.0)) return true;
  return InWedge(begin_a, end_a, begin_b) || InWedge(begin_b, end_b, begin_a);
}

// The angle of a unit direction, computed on first use: most operations never need it.
struct LazyAngle {
  Vec2 direction;
  double angle = 0.0;
  bool known = false;
  double Get() {
    if (!known) {
      angle = DetAtan2(direction.y, direction.x);
      known = true;
    }
    return angle;
  }
};

// A disk seen from the apex, for SubtractDisk (subtract = true) and IntersectDisk.
class DiskOperation {
 public:
  DiskOperation(Vec2 centre, double radius, double centre_distance, bool subtract)
      : centre_(centre),
        radius_(radius),
        centre_distance_(centre_distance),
        subtract_(subtract),
        apex_inside_(centre_distance <= radius),
        centre_distance_squared_(SquaredLength(centre)),
        swallow_limit_((1.0 - 1e-6) * radius * radius),
        far_arc_(RadialCurve::Arc(centre, radius, +1)),
        near_arc_(far_arc_.OppositeHalf()) {
    if (apex_inside_) return;
    // Tangent directions from the apex, where the circle's near and far halves meet: at the
    // half-angle asin(r / d) from the centre, so cos = t / d and sin = r / d with t = sqrt(d^2 -
    // r^2), and the unit vectors are (t c -+ r perp(c)) / d^2.
    const double d2 = centre_distance * centre_distance;
    const double tangent = std::sqrt(d2 - radius * radius);
    const Vec2 along = (tangent / d2) * centre;
    const Vec2 side = (radius / d2) * Perpendicular(centre);
    tangents_[0].direction = along - side;  // clockwise
    tangents_[1].direction = along + side;  // counter-clockwise
  }

  // False when the disk cannot meet the sector (subtract keeps it, intersect drops it): it lies
  // beyond the sector's farthest distance, inside its nearest, or outside its wedge.
  bool MayTouch(Vec2 begin, Vec2 end, double min_near, double max_far) const {
    if (centre_distance_ >= radius_ + max_far || centre_distance_ + radius_ <= min_near) {
      return false;
    }
    return apex_inside_ ||
           WedgesMayOverlap(begin, end, tangents_[0].direction, tangents_[1].direction);
  }
  bool KeepsUntouched() const { return subtract_; }
  const RadialCurve& boundary() const { return far_arc_; }

  // True when a subtracted disk certainly swallows the whole sector, so the full pass would find
  // every piece empty and drop it (in A1 at 100k points: a third of the sectors a subtraction
  // reaches, three quarters of those it drops). The sector lies
  // within its wedge between distances min_near and max_far; the squared distance from the
  // centre c to the point at distance rho along u is rho^2 - 2 rho (u . c) + |c|^2, convex in
  // rho, and u . c is smallest at a wedge end unless -c points into the wedge. The margin (a
  // millionth of r^2) dwarfs every rounding error of the bounds and of the probes' chord ends,
  // so this never claims a sector the full pass would keep a sliver of.
  bool Swallows(Vec2 begin, Vec2 end, double min_near, double max_far) const {
    if (!subtract_) return false;
    const double lowest_dot = InWedge(begin, end, -1.0 * centre_)
                                  ? -centre_distance_
                                  : std::min(Dot(begin, centre_), Dot(end, centre_));
    const auto squared_distance = [&](double rho) {
      return rho * rho - 2.0 * rho * lowest_dot + centre_distance_squared_;
    };
    return squared_distance(min_near) < swallow_limit_ &&
           squared_distance(max_far) < swallow_limit_;
  }

  int FixedCount() const { return apex_inside_ ? 0 : 2; }
  LazyAngle& Fixed(int i) { return tangents_[i]; }

  int KeptAt(Vec2 direction, KeptInterval kept[2]) const {
    const double along = Dot(centre_, direction);
    const double across = Cross(centre_, direction);
    const double discriminant = radius_ * radius_ - across * across;
    const double root = std::sqrt(discriminant > 0.0 ? discriminant : 0.0);
    const double low = along - root;
    const double high = along + root;
    if (apex_inside_) {
      if (subtract_) {
        kept[0] = {&far_arc_, high, nullptr, 0.0};
      } else {
        kept[0] = {nullptr, 0.0, &far_arc_, high};
      }
      return 1;
    }
    const bool ray_meets_disk = discriminant > 0.0 && along > 0.0;
    if (subtract_) {
      if (!ray_meets_disk) {
        kept[0] = {nullptr, 0.0, nullptr, 0.0};
        return 1;
      }
      kept[0] = {nullptr, 0.0, &near_arc_, low};
      kept[1] = {&far_arc_, high, nullptr, 0.0};
      return 2;
    }
    if (!ray_meets_disk) return 0;
    kept[0] = {&near_arc_, low, &far_arc_, high};
    return 1;
  }

 private:
  Vec2 centre_;
  double radius_;
  double centre_distance_;
  bool subtract_;
  bool apex_inside_;
  double centre_distance_squared_;
  double swallow_limit_;  // Swallows' bound on squared distances
  RadialCurve far_arc_;
  RadialCurve near_arc_;
  LazyAngle tangents_[2];
};

// The half-plane {x : Dot(normal, x) <= offset}, apex-relative.
class HalfPlaneOperation {
 public:
  HalfPlaneOperation(Vec2 normal, double offset)
      : normal_(normal), offset_(offset), line_(RadialCurve::Line(normal, offset)) {
    // Rays parallel to the line, where the kept interval switches between bounded and unbounded.
    parallels_[0].direction = {-normal_.y, normal_.x};
    parallels_[1].direction = {normal_.y, -normal_.x};
  }

  // A sector entirely within distance `offset` of the apex lies inside the half-plane.
  bool MayTouch(Vec2, Vec2, double, double max_far) const { return !(offset_ >= max_far); }
  bool KeepsUntouched() const { return true; }
  bool Swallows(Vec2, Vec2, double, double) const { return false; }
  const RadialCurve& boundary() const { return line_; }

  int FixedCount() const { return 2; }
  LazyAngle& Fixed(int i) { return parallels_[i]; }

  int KeptAt(Vec2 direction, KeptInterval kept[2]) const {
    // Along the ray s * direction: s * q <= offset.
    const double q = Dot(normal_, direction);
    if (offset_ > 0.0) {
      if (q > 0.0) {
        kept[0] = {nullptr, 0.0, &line_, offset_ / q};
      } else {
        kept[0] = {nullptr, 0.0, nullptr, 0.0};
      }
      return 1;
    }
    if (q >= 0.0) return 0;
    if (offset_ == 0.0) {
      kept[0] = {nullptr, 0.0, nullptr, 0.0};
    } else {
      kept[0] = {&line_, offset_ / q, nullptr, 0.0};
    }
    return 1;
  }

 private:
  Vec2 normal_;
  double offset_;
  RadialCurve line_;
  LazyAngle parallels_[2];
};

// Where, as a fraction of a piece's width, its bounding curves are compared (golden sections).
constexpr double kFirstProbe = 0.381966011250105;
constexpr double kSecondProbe = 0.7236067977499790;

// The curves bounding one surviving radial interval of a piece.
struct PieceBounds {
  const RadialCurve* lower;
  const RadialCurve* upper;
};

// Intersects the sector's interval [near, far] along `direction` with what `operation` keeps
// there, writing the bounding curves of each non-empty result, and returns the smallest distance
// gap among the comparisons made: how close this probe is to a tie.
template <typename Operation>
double ClassifyAlong(const Operation& operation, const ScallopedSector& sector, Vec2 direction,
                     PieceBounds bounds[2], int& bounds_count) {
  const double g = sector.near.DistanceAlong(direction);
  const double h = sector.far.DistanceAlong(direction);
  KeptInterval kept[2];
  const int kept_count = operation.KeptAt(direction, kept);
  double margin = std::numeric_limits<double>::infinity();
  bounds_count = 0;
  for (int k = 0; k < kept_count; ++k) {
    if (kept[k].lower != nullptr) margin = std::min(margin, std::fabs(g - kept[k].lower_distance));
    if (kept[k].upper != nullptr) margin = std::min(margin, std::fabs(h - kept[k].upper_distance));
    // Ties go to the old curve so untouched pieces merge back into the original sector.
    const bool old_lower = kept[k].lower == nullptr || g >= kept[k].lower_distance;
    const bool old_upper = kept[k].upper == nullptr || h <= kept[k].upper_distance;
    const double lower_distance = old_lower ? g : kept[k].lower_distance;
    const double upper_distance = old_upper ? h : kept[k].upper_distance;
    margin = std::min(margin, std::fabs(upper_distance - lower_distance));
    if (!(upper_distance > lower_distance)) continue;
    bounds[bounds_count++] = {old_lower ? &sector.near : kept[k].lower,
                              old_upper ? &sector.far : kept[k].upper};
  }
  return margin;
}

// Critical angles of one sector with their unit directions, so that areas and probes need no
// further trigonometry. At most 2 fixed angles + 2 crossings with each of near and far + 2 ends.
struct CriticalAngles {
  double angles[8];
  Vec2 directions[8];
  int count = 0;

  void AddIfInside(double angle, Vec2 direction, double begin, double end) {
    if (angle > begin && angle < end) {
      angles[count] = angle;
      directions[count] = direction;
      ++count;
    }
  }
  // Insertion sort of entries [1, count): at most six, and std::sort trips -Warray-bounds here.
  void SortInterior() {
    for (int i = 2; i < count; ++i) {
      const double angle = angles[i];
      const Vec2 direction = directions[i];
      int j = i;
      for (; j > 1 && angles[j - 1] > angle; --j) {
        angles[j] = angles[j - 1];
        directions[j] = directions[j - 1];
      }
      angles[j] = angle;
      directions[j] = direction;
    }
  }
};

// A run of consecutive pieces [first, last] (indices of critical angles) with the same bounds.
struct PieceRun {
  int first;
  int last;
  const RadialCurve* lower;
  const RadialCurve* upper;
};

// RadialCurve::HalfSquareIntegralRemainder of the (at most four) curves of one sector's split at
// its critical angles, each computed once: neighbouring runs share their end angles and curves.
// The curves are the sector's own two (slots 0, 1, known in advance) and at most two of the
// operation's (a disk's two halves, or one line), so a slot is found by at most three compares.
class RemainderMemo {
 public:
  RemainderMemo(const CriticalAngles& critical, const ScallopedSector& sector)
      : critical_(critical), curves_{&sector.near, &sector.far, nullptr, nullptr} {}

  double At(const RadialCurve* curve, int index) {
    const int slot = SlotOf(curve);
    const uint32_t bit = KnownBit(slot, index);
    if (!(known_ & bit)) {
      values_[slot][index] = curve->HalfSquareIntegralRemainder(critical_.directions[index]);
      known_ |= bit;
    }
    return values_[slot][index];
  }

  // Records a value the caller computed earlier by the same call (the sector's own ends), so the
  // memo returns the same bits without recomputing them.
  void Know(const RadialCurve* curve, int index, double value) {
    const int slot = SlotOf(curve);
    values_[slot][index] = value;
    known_ |= KnownBit(slot, index);
  }

 private:
  static uint32_t KnownBit(int slot, int index) { return uint32_t{1} << (8 * slot + index); }

  int SlotOf(const RadialCurve* curve) {
    if (curve == curves_[0]) return 0;
    if (curve == curves_[1]) return 1;
    if (curve == curves_[2]) return 2;
    if (curves_[2] == nullptr) {
      curves_[2] = curve;
      return 2;
    }
    curves_[3] = curve;
    return 3;
  }

  const CriticalAngles& critical_;
  const RadialCurve* curves_[4];
  uint32_t known_ = 0;  // bit 8 slot + index: values_[slot][index] is set
  double values_[4][8];
};

}  // namespace

ScallopedRegion ScallopedRegion::Annulus(Vec2 apex, double inner, double outer) {
  ScallopedRegion region;
  region.Reset(apex, inner, outer);
  return region;
}

void ScallopedRegion::Reset(Vec2 apex, double inner, double outer) {
  apex_ = apex;
  sectors_.clear();
  sector_cache_.clear();
  const RadialCurve near = RadialCurve::Arc({0.0, 0.0}, inner, +1);
  const RadialCurve far = RadialCurve::Arc({0.0, 0.0}, outer, +1);
  sectors_.push_back({-kPi, 0.0, near, far});
  sectors_.push_back({0.0, kPi, near, far});
  const Vec2 minus_pi = UnitAt(-kPi);
  const Vec2 zero = UnitAt(0.0);
  const Vec2 plus_pi = UnitAt(kPi);
  sector_cache_.push_back({AreaBetween(near, far, -kPi, minus_pi, 0.0, zero),
                           SectorEnds::Of(sectors_[0], minus_pi, zero), inner, outer});
  sector_cache_.push_back({AreaBetween(near, far, 0.0, zero, kPi, plus_pi),
                           SectorEnds::Of(sectors_[1], zero, plus_pi), inner, outer});
  area_ = sector_cache_[0].area + sector_cache_[1].area;
  outer_bound_ = outer;
  inner_bound_ = inner;
  negligible_area_ = kNegligibleAreaFraction * area_;
}

void ScallopedRegion::AssignMoved(const ScallopedRegion& shape, Vec2 apex) {
  *this = shape;  // vector assignment reuses capacity
  apex_ = apex;
}

void ScallopedRegion::EraseSector(size_t index) {
  const auto offset = static_cast<std::ptrdiff_t>(index);
  sectors_.erase(sectors_.begin() + offset);
  sector_cache_.erase(sector_cache_.begin() + offset);
}

void ScallopedRegion::Clear() {
  sectors_.clear();
  sector_cache_.clear();
  area_ = 0.0;
}

template <typename Operation>
void ScallopedRegion::Apply(Operation& operation) {
  // Distances closer than this at a probe count as a tie (rounding-level relative to the region).
  const double tie_tolerance = 1e-9 * outer_bound_;
  const int fixed_count = operation.FixedCount();
  bool changed = false;
  // Back to front, so replacing sector `index` by several moves only sectors already done.
  for (size_t index = sectors_.size(); index-- > 0;) {
    const ScallopedSector& sector = sectors_[index];
    const SectorCache& cache = sector_cache_[index];
    const Vec2 begin_direction = cache.ends.begin_direction;
    const Vec2 end_direction = cache.ends.end_direction;
    if (!operation.MayTouch(begin_direction, end_direction, cache.min_near, cache.max_far)) {
      if (!operation.KeepsUntouched()) {
        EraseSector(index);
        changed = true;
      }
      continue;
    }
    if (operation.Swallows(begin_direction, end_direction, cache.min_near, cache.max_far)) {
      EraseSector(index);
      changed = true;
      continue;
    }
    const double begin = sector.angle_begin;
    const double end = sector.angle_end;
    CriticalAngles critical;
    critical.angles[0] = begin;
    critical.directions[0] = begin_direction;
    critical.count = 1;
    for (int i = 0; i < fixed_count; ++i) {
      LazyAngle& fixed = operation.Fixed(i);
      // Cross products first: the angle (an atan2) only for directions inside the wedge.
      if (Cross(begin_direction, fixed.direction) > 0.0 &&
          Cross(fixed.direction, end_direction) > 0.0) {
        critical.AddIfInside(fixed.Get(), fixed.direction, begin, end);
      }
    }
    Vec2 points[2];
    for (const RadialCurve* curve : {&sector.near, &sector.far}) {
      const int crossings = CurveCrossings(operation.boundary(), *curve, points);
      for (int i = 0; i < crossings; ++i) {
        // Sectors are at most pi wide, so two cross products reject crossings outside the wedge
        // before paying for an atan2 (this also drops a crossing at the apex, which splits no ray).
        if (!(Cross(begin_direction, points[i]) > 0.0 && Cross(points[i], end_direction) > 0.0)) {
          continue;
        }
        critical.AddIfInside(DetAtan2(points[i].y, points[i].x), Normalized(points[i]), begin,
                             end);
      }
    }
    critical.SortInterior();
    critical.angles[critical.count] = end;
    critical.directions[critical.count] = end_direction;
    ++critical.count;

    // Each piece yields at most two runs (a subtracted disk splits a ray's interval in two).
    PieceRun runs[14];
    int run_count = 0;
    for (int i = 0; i + 1 < critical.count; ++i) {
      const double piece_begin = critical.angles[i];
      const double piece_end = critical.angles[i + 1];
      const double width = piece_end - piece_begin;
      if (!(width > 0.0)) continue;
      // Probe off-centre: symmetric configurations (a disk tangent to a circle, a line tangent to
      // the inner circle) touch exactly at a piece's mid-angle, where a tie hides the piece.
      // Two distinct circles (or a circle and a line) touch at most once without crossing, so if
      // the first probe is close to a tie the second one is not, unless the curves coincide.
      // Any ray inside the piece will do, so interpolate directions instead of calling sincos.
      // Chords between the ends are fine below a right angle; wider pieces (up to pi) go through
      // the direction a right angle past the start, which lies inside them.
      const Vec2 first = critical.directions[i];
      const Vec2 last = critical.directions[i + 1];
      const auto probe = [&](double fraction) {
        if (width < 2.0) return Normalized((1.0 - fraction) * first + fraction * last);
        const Vec2 middle = Perpendicular(first);
        return fraction < 0.5 ? Normalized(first + middle) : Normalized(middle + last);
      };
      PieceBounds bounds[2];
      int bounds_count = 0;
      const double margin =
          ClassifyAlong(operation, sector, probe(kFirstProbe), bounds, bounds_count);
      if (margin <= tie_tolerance) {
        PieceBounds second[2];
        int second_count = 0;
        if (ClassifyAlong(operation, sector, probe(kSecondProbe), second, second_count) > margin) {
          std::copy(second, second + second_count, bounds);
          bounds_count = second_count;
        }
      }
      for (int k = 0; k < bounds_count; ++k) {
        bool merged = false;
        for (int r = 0; r < run_count; ++r) {
          PieceRun& run = runs[r];
          if (run.last == i && run.lower == bounds[k].lower && run.upper == bounds[k].upper) {
            run.last = i + 1;
            merged = true;
            break;
          }
        }
        if (!merged) runs[run_count++] = {i, i + 1, bounds[k].lower, bounds[k].upper};
      }
    }
    if (run_count == 1 && runs[0].first == 0 && runs[0].last == critical.count - 1 &&
        runs[0].lower == &sector.near && runs[0].upper == &sector.far) {
      continue;  // untouched after all: leave it where it is
    }
    // Areas first, so the vectors are resized once and written in place.
    double areas[14];
    double run_ends[14][4];  // each run's SectorEnds remainders: near_begin, near_end, far_...
    int kept = 0;
    RemainderMemo remainders(critical, sector);
    // The sector's own curves at its own ends: computed when it was made.
    const int last = critical.count - 1;
    remainders.Know(&sector.near, 0, cache.ends.near_begin);
    remainders.Know(&sector.near, last, cache.ends.near_end);
    remainders.Know(&sector.far, 0, cache.ends.far_begin);
    remainders.Know(&sector.far, last, cache.ends.far_end);
    for (int r = 0; r < run_count; ++r) {
      const PieceRun& run = runs[r];
      double* ends = run_ends[r];
      ends[0] = remainders.At(run.lower, run.first);
      ends[1] = remainders.At(run.lower, run.last);
      ends[2] = remainders.At(run.upper, run.first);
      ends[3] = remainders.At(run.upper, run.last);
      areas[r] = (run.upper->LinearCoefficient() - run.lower->LinearCoefficient()) *
                     (critical.angles[run.last] - critical.angles[run.first]) +
                 ((ends[3] - ends[2]) - (ends[1] - ends[0]));
      if (!(areas[r] > negligible_area_)) {
        // Small: keep it only if it is a real gap, wider than rounding noise.
        const double middle = 0.5 * (critical.angles[run.first] + critical.angles[run.last]);
        const double width = run.upper->DistanceAt(middle) - run.lower->DistanceAt(middle);
        if (!(areas[r] > 0.0 && width > kNegligibleWidthFraction * outer_bound_)) areas[r] = 0.0;
      }
      if (areas[r] > 0.0) ++kept;
    }
    changed = true;
    const auto offset = static_cast<std::ptrdiff_t>(index);
    if (kept == 0) {
      EraseSector(index);
      continue;
    }
    // The runs point into the old sector, which the insertion may move: keep a copy.
    const ScallopedSector old = sector;
    const SectorCache old_cache = cache;
    const auto original = [&](const RadialCurve* curve) {
      return curve == &sector.near ? &old.near : curve == &sector.far ? &old.far : curve;
    };
    if (kept > 1) {
      sectors_.insert(sectors_.begin() + offset + 1, static_cast<size_t>(kept - 1), old);
      sector_cache_.insert(sector_cache_.begin() + offset + 1, static_cast<size_t>(kept - 1),
                           old_cache);
    }
    size_t out = index;
    for (int r = 0; r < run_count; ++r) {
      if (!(areas[r] > 0.0)) continue;
      const PieceRun& run = runs[r];
      const RadialCurve* lower = original(run.lower);
      const RadialCurve* upper = original(run.upper);
      ScallopedSector& piece = sectors_[out];
      piece.angle_begin = critical.angles[run.first];
      piece.angle_end = critical.angles[run.last];
      piece.near = *lower;
      piece.far = *upper;
      SectorCache& piece_cache = sector_cache_[out];
      piece_cache.area = areas[r];
      piece_cache.ends = {critical.directions[run.first],
                          critical.directions[run.last],
                          run_ends[r][0],
                          run_ends[r][1],
                          run_ends[r][2],
                          run_ends[r][3]};
      piece_cache.min_near =
          lower == &old.near ? old_cache.min_near : std::max(inner_bound_, lower->MinDistance());
      piece_cache.max_far =
          upper == &old.far ? old_cache.max_far : std::min(outer_bound_, upper->MaxDistance());
      ++out;
    }
  }
  if (!changed) return;
  double total = 0.0;
  for (const SectorCache& cache : sector_cache_) total += cache.area;
  area_ = total;
}

void ScallopedRegion::SubtractDisk(Vec2 centre, double radius) {
  if (sectors_.empty()) return;
  const Vec2 relative = centre - apex_;
  const double distance = FastLength(relative);
  if (distance >= radius + outer_bound_ || distance + radius <= inner_bound_) return;
  if (distance + outer_bound_ <= radius) {
    Clear();
    return;
  }
  DiskOperation operation(relative, radius, distance, /*subtract=*/true);
  Apply(operation);
}

void ScallopedRegion::IntersectDisk(Vec2 centre, double radius) {
  if (sectors_.empty()) return;
  const Vec2 relative = centre - apex_;
  const double distance = FastLength(relative);
  if (distance + outer_bound_ <= radius) return;
  if (distance >= radius + outer_bound_ || distance + radius <= inner_bound_) {
    Clear();
    return;
  }
  DiskOperation operation(relative, radius, distance, /*subtract=*/false);
  Apply(operation);
  outer_bound_ = std::min(outer_bound_, distance + radius);
  inner_bound_ = std::max(inner_bound_, distance - radius);
}

void ScallopedRegion::IntersectHalfPlane(Vec2 unit_normal, double offset) {
  if (sectors_.empty()) return;
  const double relative_offset = offset - Dot(unit_normal, apex_);
  if (relative_offset >= outer_bound_) return;
  if (relative_offset <= -outer_bound_) {
    Clear();
    return;
  }
  HalfPlaneOperation operation(unit_normal, relative_offset);
  Apply(operation);
}

Vec2 ScallopedRegion::Sample(double u0, double u1, double u2) const {
  double remaining = u0 * area_;
  size_t chosen = sectors_.size() - 1;
  for (size_t i = 0; i < sectors_.size(); ++i) {
    if (remaining < sector_cache_[i].area) {
      chosen = i;
      break;
    }
    remaining -= sector_cache_[i].area;
  }
  return apex_ + sectors_[chosen].Sample(u1, u2, sector_cache_[chosen].ends);
}

void ScallopedRegion::Prefetch() const {
  // Every operation scans the whole cache array; the sectors are read where an operation reaches
  // them. A few lines of each cover the usual handful of sectors.
  constexpr size_t kLine = 64;
  constexpr size_t kMaxLines = 8;
  const auto request = [](const void* data, size_t bytes) {
    const char* first = static_cast<const char*>(data);
    for (size_t offset = 0; offset < std::min(bytes, kLine * kMaxLines); offset += kLine) {
      __builtin_prefetch(first + offset);
    }
  };
  request(sector_cache_.data(), sector_cache_.size() * sizeof(SectorCache));
  request(sectors_.data(), sectors_.size() * sizeof(ScallopedSector));
}

bool ScallopedRegion::Contains(Vec2 p) const {
  const Vec2 relative = p - apex_;
  const double distance = Length(relative);
  if (distance == 0.0) {
    for (const ScallopedSector& sector : sectors_) {
      if (sector.Contains(relative)) return true;
    }
    return false;
  }
  const double angle = DetAtan2(relative.y, relative.x);
  const Vec2 direction = (1.0 / distance) * relative;
  for (const ScallopedSector& sector : sectors_) {
    if (sector.ContainsPolar(angle, direction, distance)) return true;
  }
  return false;
}

}  // namespace scallop
