// ScallopedRegion set operations. Every operation is one generic pass (Apply): per sector, split
// the angular range at the critical angles where the ordering of the bounding distances can
// change, decide at each piece's mid-angle which radial intervals survive and which curve bounds
// them, then merge neighbouring pieces with identical curves.
#include "scallop/geometry/scalloped_region.h"

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

// Whether [begin, end] (inside [-pi, pi]) overlaps the angular span [span_begin, span_end], which
// wraps through pi when span_end < span_begin.
bool OverlapsSpan(double begin, double end, double span_begin, double span_end) {
  if (span_begin <= span_end) return begin < span_end && span_begin < end;
  return (begin < span_end + 2.0 * kPi && span_begin < end) ||
         (begin < span_end && span_begin - 2.0 * kPi < end);
}

// A disk seen from the apex, for SubtractDisk (subtract = true) and IntersectDisk.
class DiskOperation {
 public:
  DiskOperation(Vec2 centre, double radius, double centre_distance, bool subtract)
      : centre_(centre),
        radius_(radius),
        subtract_(subtract),
        apex_inside_(centre_distance <= radius),
        far_arc_(RadialCurve::Arc(centre, radius, +1)),
        near_arc_(far_arc_.OppositeHalf()) {
    if (apex_inside_) return;
    // Tangent points from the apex: where the circle's near and far halves meet.
    const double d2 = centre_distance * centre_distance;
    const double r2 = radius * radius;
    const Vec2 base = (1.0 - r2 / d2) * centre;
    const Vec2 side = (radius * std::sqrt(d2 - r2) / d2) * Perpendicular(centre);
    const Vec2 clockwise = base - side;
    const Vec2 counter_clockwise = base + side;
    span_begin_ = std::atan2(clockwise.y, clockwise.x);
    span_end_ = std::atan2(counter_clockwise.y, counter_clockwise.x);
    span_begin_direction_ = Normalized(clockwise);
    span_end_direction_ = Normalized(counter_clockwise);
  }

  // Sectors whose wedge the disk cannot reach: subtract keeps them, intersect drops them.
  bool MayTouch(const ScallopedSector& sector) const {
    return apex_inside_ ||
           OverlapsSpan(sector.angle_begin, sector.angle_end, span_begin_, span_end_);
  }
  bool KeepsUntouched() const { return subtract_; }
  const RadialCurve& boundary() const { return far_arc_; }

  int FixedAngles(double angles[2], Vec2 directions[2]) const {
    if (apex_inside_) return 0;
    angles[0] = span_begin_;
    angles[1] = span_end_;
    directions[0] = span_begin_direction_;
    directions[1] = span_end_direction_;
    return 2;
  }

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
  bool subtract_;
  bool apex_inside_;
  RadialCurve far_arc_;
  RadialCurve near_arc_;
  double span_begin_ = -kPi;
  double span_end_ = kPi;
  Vec2 span_begin_direction_;
  Vec2 span_end_direction_;
};

// The half-plane {x : Dot(normal, x) <= offset}, apex-relative.
class HalfPlaneOperation {
 public:
  HalfPlaneOperation(Vec2 normal, double offset)
      : normal_(normal), offset_(offset), line_(RadialCurve::Line(normal, offset)) {}

  bool MayTouch(const ScallopedSector&) const { return true; }
  bool KeepsUntouched() const { return true; }
  const RadialCurve& boundary() const { return line_; }

  // Rays parallel to the line, where the kept interval switches between bounded and unbounded.
  int FixedAngles(double angles[2], Vec2 directions[2]) const {
    directions[0] = {-normal_.y, normal_.x};
    directions[1] = {normal_.y, -normal_.x};
    angles[0] = std::atan2(directions[0].y, directions[0].x);
    angles[1] = std::atan2(directions[1].y, directions[1].x);
    return 2;
  }

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

}  // namespace

ScallopedRegion ScallopedRegion::Annulus(Vec2 apex, double inner, double outer) {
  ScallopedRegion region;
  region.apex_ = apex;
  const RadialCurve near = RadialCurve::Arc({0.0, 0.0}, inner, +1);
  const RadialCurve far = RadialCurve::Arc({0.0, 0.0}, outer, +1);
  region.sectors_.push_back({-kPi, 0.0, near, far});
  region.sectors_.push_back({0.0, kPi, near, far});
  for (const ScallopedSector& sector : region.sectors_) {
    region.sector_cache_.push_back(
        {sector.Area(), UnitAt(sector.angle_begin), UnitAt(sector.angle_end)});
  }
  region.area_ = region.sector_cache_[0].area + region.sector_cache_[1].area;
  region.outer_bound_ = outer;
  region.inner_bound_ = inner;
  region.negligible_area_ = kNegligibleAreaFraction * region.area_;
  return region;
}

void ScallopedRegion::Clear() {
  sectors_.clear();
  sector_cache_.clear();
  area_ = 0.0;
}

template <typename Operation>
void ScallopedRegion::Apply(const Operation& operation) {
  scratch_sectors_.clear();
  scratch_cache_.clear();
  double total = 0.0;
  // Distances closer than this at a probe count as a tie (rounding-level relative to the region).
  const double tie_tolerance = 1e-9 * outer_bound_;
  double fixed[2];
  Vec2 fixed_directions[2];
  const int fixed_count = operation.FixedAngles(fixed, fixed_directions);
  for (size_t index = 0; index < sectors_.size(); ++index) {
    const ScallopedSector& sector = sectors_[index];
    if (!operation.MayTouch(sector)) {
      if (operation.KeepsUntouched()) {
        scratch_sectors_.push_back(sector);
        scratch_cache_.push_back(sector_cache_[index]);
        total += sector_cache_[index].area;
      }
      continue;
    }
    const double begin = sector.angle_begin;
    const double end = sector.angle_end;
    const Vec2 begin_direction = sector_cache_[index].begin_direction;
    const Vec2 end_direction = sector_cache_[index].end_direction;
    CriticalAngles critical;
    critical.angles[0] = begin;
    critical.directions[0] = begin_direction;
    critical.count = 1;
    for (int i = 0; i < fixed_count; ++i) {
      critical.AddIfInside(fixed[i], fixed_directions[i], begin, end);
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
        critical.AddIfInside(std::atan2(points[i].y, points[i].x), Normalized(points[i]), begin,
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
    for (int r = 0; r < run_count; ++r) {
      const PieceRun& run = runs[r];
      const bool unchanged = run.first == 0 && run.last == critical.count - 1 &&
                             run.lower == &sector.near && run.upper == &sector.far;
      double area = sector_cache_[index].area;
      if (!unchanged) {
        const double t0 = critical.angles[run.first];
        const double t1 = critical.angles[run.last];
        const Vec2 e0 = critical.directions[run.first];
        const Vec2 e1 = critical.directions[run.last];
        area = (run.upper->HalfSquareIntegralAlong(t1, e1) -
                run.upper->HalfSquareIntegralAlong(t0, e0)) -
               (run.lower->HalfSquareIntegralAlong(t1, e1) -
                run.lower->HalfSquareIntegralAlong(t0, e0));
      }
      if (!(area > negligible_area_)) continue;
      scratch_sectors_.push_back(
          {critical.angles[run.first], critical.angles[run.last], *run.lower, *run.upper});
      scratch_cache_.push_back(
          {area, critical.directions[run.first], critical.directions[run.last]});
      total += area;
    }
  }
  sectors_.swap(scratch_sectors_);
  sector_cache_.swap(scratch_cache_);
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
  Apply(DiskOperation(relative, radius, distance, /*subtract=*/true));
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
  Apply(DiskOperation(relative, radius, distance, /*subtract=*/false));
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
  Apply(HalfPlaneOperation(unit_normal, relative_offset));
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
  return apex_ + sectors_[chosen].Sample(u1, u2);
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
  const double angle = std::atan2(relative.y, relative.x);
  const Vec2 direction = (1.0 / distance) * relative;
  for (const ScallopedSector& sector : sectors_) {
    if (sector.ContainsPolar(angle, direction, distance)) return true;
  }
  return false;
}

}  // namespace scallop
