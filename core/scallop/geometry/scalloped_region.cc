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
        near_arc_(RadialCurve::Arc(centre, radius, -1)),
        far_arc_(RadialCurve::Arc(centre, radius, +1)) {
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
  }

  // Sectors whose wedge the disk cannot reach: subtract keeps them, intersect drops them.
  bool MayTouch(const ScallopedSector& sector) const {
    return apex_inside_ ||
           OverlapsSpan(sector.angle_begin, sector.angle_end, span_begin_, span_end_);
  }
  bool KeepsUntouched() const { return subtract_; }
  const RadialCurve& boundary() const { return far_arc_; }

  int FixedAngles(double angles[2]) const {
    if (apex_inside_) return 0;
    angles[0] = span_begin_;
    angles[1] = span_end_;
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
  RadialCurve near_arc_;
  RadialCurve far_arc_;
  double span_begin_ = -kPi;
  double span_end_ = kPi;
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
  int FixedAngles(double angles[2]) const {
    angles[0] = std::atan2(normal_.x, -normal_.y);
    angles[1] = std::atan2(-normal_.x, normal_.y);
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

// Adds `angle` to `angles` when strictly inside (begin, end).
inline void AddIfInside(double angle, double begin, double end, double* angles, int& count) {
  if (angle > begin && angle < end) angles[count++] = angle;
}

}  // namespace

ScallopedRegion ScallopedRegion::Annulus(Vec2 apex, double inner, double outer) {
  ScallopedRegion region;
  region.apex_ = apex;
  const RadialCurve near = RadialCurve::Arc({0.0, 0.0}, inner, +1);
  const RadialCurve far = RadialCurve::Arc({0.0, 0.0}, outer, +1);
  region.sectors_.push_back({-kPi, 0.0, near, far});
  region.sectors_.push_back({0.0, kPi, near, far});
  for (const ScallopedSector& sector : region.sectors_) {
    region.sector_areas_.push_back(sector.Area());
  }
  region.area_ = region.sector_areas_[0] + region.sector_areas_[1];
  region.outer_bound_ = outer;
  region.inner_bound_ = inner;
  region.negligible_area_ = kNegligibleAreaFraction * region.area_;
  return region;
}

void ScallopedRegion::Clear() {
  sectors_.clear();
  sector_areas_.clear();
  area_ = 0.0;
}

template <typename Operation>
void ScallopedRegion::Apply(const Operation& operation) {
  scratch_sectors_.clear();
  scratch_areas_.clear();
  double total = 0.0;
  // Distances closer than this at a probe count as a tie (rounding-level relative to the region).
  const double tie_tolerance = 1e-9 * outer_bound_;
  double fixed[2];
  const int fixed_count = operation.FixedAngles(fixed);
  for (size_t index = 0; index < sectors_.size(); ++index) {
    const ScallopedSector& sector = sectors_[index];
    if (!operation.MayTouch(sector)) {
      if (operation.KeepsUntouched()) {
        scratch_sectors_.push_back(sector);
        scratch_areas_.push_back(sector_areas_[index]);
        total += sector_areas_[index];
      }
      continue;
    }
    const double begin = sector.angle_begin;
    const double end = sector.angle_end;
    // Critical angles: at most 2 fixed + 2 crossings with each of near and far, plus the ends.
    double angles[8];
    int count = 0;
    angles[count++] = begin;
    for (int i = 0; i < fixed_count; ++i) AddIfInside(fixed[i], begin, end, angles, count);
    Vec2 points[2];
    for (const RadialCurve* curve : {&sector.near, &sector.far}) {
      const int crossings = CurveCrossings(operation.boundary(), *curve, points);
      for (int i = 0; i < crossings; ++i) {
        AddIfInside(std::atan2(points[i].y, points[i].x), begin, end, angles, count);
      }
    }
    // Insertion sort: at most six entries, and std::sort trips GCC 12's -Warray-bounds here.
    for (int i = 2; i < count; ++i) {
      const double value = angles[i];
      int j = i;
      for (; j > 1 && angles[j - 1] > value; --j) angles[j] = angles[j - 1];
      angles[j] = value;
    }
    angles[count++] = end;

    // Each piece yields at most two sectors (a subtracted disk splits a ray's interval in two).
    ScallopedSector pieces[14];
    int piece_count = 0;
    for (int i = 0; i + 1 < count; ++i) {
      const double piece_begin = angles[i];
      const double piece_end = angles[i + 1];
      if (!(piece_end > piece_begin)) continue;
      // Probe off-centre: symmetric configurations (a disk tangent to a circle, a line tangent to
      // the inner circle) touch exactly at a piece's mid-angle, where a tie hides the piece.
      // Two distinct circles (or a circle and a line) touch at most once without crossing, so if
      // the first probe is close to a tie the second one is not, unless the curves coincide.
      PieceBounds bounds[2];
      int bounds_count = 0;
      const double width = piece_end - piece_begin;
      const double margin = ClassifyAlong(operation, sector,
                                          UnitAt(piece_begin + kFirstProbe * width), bounds,
                                          bounds_count);
      if (margin <= tie_tolerance) {
        PieceBounds second[2];
        int second_count = 0;
        if (ClassifyAlong(operation, sector, UnitAt(piece_begin + kSecondProbe * width), second,
                          second_count) > margin) {
          std::copy(second, second + second_count, bounds);
          bounds_count = second_count;
        }
      }
      for (int k = 0; k < bounds_count; ++k) {
        const RadialCurve& lower = *bounds[k].lower;
        const RadialCurve& upper = *bounds[k].upper;
        bool merged = false;
        for (int p = 0; p < piece_count; ++p) {
          ScallopedSector& previous = pieces[p];
          if (previous.angle_end == piece_begin && previous.near == lower && previous.far == upper) {
            previous.angle_end = piece_end;
            merged = true;
            break;
          }
        }
        if (!merged) pieces[piece_count++] = {piece_begin, piece_end, lower, upper};
      }
    }
    for (int p = 0; p < piece_count; ++p) {
      const ScallopedSector& piece = pieces[p];
      const bool unchanged = piece.angle_begin == begin && piece.angle_end == end &&
                             piece.near == sector.near && piece.far == sector.far;
      const double area = unchanged ? sector_areas_[index] : piece.Area();
      if (!(area > negligible_area_)) continue;
      scratch_sectors_.push_back(piece);
      scratch_areas_.push_back(area);
      total += area;
    }
  }
  sectors_.swap(scratch_sectors_);
  sector_areas_.swap(scratch_areas_);
  area_ = total;
}

void ScallopedRegion::SubtractDisk(Vec2 centre, double radius) {
  if (sectors_.empty()) return;
  const Vec2 relative = centre - apex_;
  const double distance = Length(relative);
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
  const double distance = Length(relative);
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
    if (remaining < sector_areas_[i]) {
      chosen = i;
      break;
    }
    remaining -= sector_areas_[i];
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
