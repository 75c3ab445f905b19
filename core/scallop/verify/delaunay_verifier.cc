// The verifier's Delaunay scan: the only translation unit that includes CGAL
// (it compiles slowly and needs GMP and MPFR), so nothing else pays for it.
// See delaunay_verifier.h for what is judged and docs/design.md for why.
#include "scallop/verify/delaunay_verifier.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/Triangulation_data_structure_2.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

namespace scallop {
namespace {

// Exact predicates keep the triangulation exactly Delaunay whatever the
// rounding; the constructions (circumcentres) are doubles and are only used
// to find where F1 peaks, never to decide spacing.
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<uint32_t, Kernel>;
using FaceBase = CGAL::Triangulation_face_base_with_info_2<uint32_t, Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, Tds>;
using CgalPoint = Kernel::Point_2;

// Input counts above this could overflow the 32-bit vertex info once a torus
// replicates every point into nine images.
constexpr size_t kMaxVerifiedPoints = 200'000'000;

// A vertex of the triangulated set: an input point or, on a torus, a translate.
struct LiftedPoint {
  Vec2 position;
  uint32_t index = 0;  // into the input span
  int8_t shift_x = 0;  // in torus widths
  int8_t shift_y = 0;  // in torus heights
};

enum class PairRule {
  kEvery,          // a rectangle: every Delaunay edge
  kTorusOnce,      // a torus: one translate of each pair
  kTouchesWindow,  // a window: edges with an end inside the half-open window
};

struct Judging {
  std::span<const Vec2> points;
  Rect area;  // closed area whose empty circles are judged; pairs use it half-open
  PairRule pair_rule = PairRule::kEvery;
  double width = 0.0;  // torus periods
  double height = 0.0;
  double min_distance = 1.0;
  VerifyOptions options;
};

Vec2 PositionOf(Delaunay::Vertex_handle v) { return {v->point().x(), v->point().y()}; }

Vec2 ClampTo(const Rect& r, Vec2 p) {
  return {std::clamp(p.x, r.x0, r.x1), std::clamp(p.y, r.y0, r.y1)};
}

bool WithinClosed(const Rect& r, Vec2 p, double slack) {
  return r.x0 - slack <= p.x && p.x <= r.x1 + slack && r.y0 - slack <= p.y && p.y <= r.y1 + slack;
}

class Scan {
 public:
  Scan(const Judging& judging, const std::vector<LiftedPoint>& lifted, VerifyReport& report)
      : judging_(judging), lifted_(lifted), report_(report) {
    const double d = judging.min_distance;
    squared_min_distance_ = d * d;
    // Where the boundary and the circumcentres meet, rounding decides whether
    // a candidate lies in the area. Candidates within this slack are kept and
    // their F1 re-measured at the nearest spot of the area, so a generous
    // slack costs a few nearest-vertex queries and never inflates the radius.
    slack_ = 1e-6 * d;
  }

  // Runs the scan; false when options.stop stopped it (the report is then
  // incomplete and must not be used).
  bool Run() {
    using IndexedPoint = std::pair<CgalPoint, uint32_t>;
    std::vector<IndexedPoint> input;
    input.reserve(lifted_.size());
    for (size_t i = 0; i < lifted_.size(); ++i) {
      input.emplace_back(CgalPoint(lifted_[i].position.x, lifted_[i].position.y),
                         static_cast<uint32_t>(i));
    }
    // Inserting in Hilbert order, each from the previous vertex, makes point
    // location O(1). Sorting the pairs themselves rather than indices into
    // them (as CGAL's insert-with-info does) keeps the walk cache-friendly:
    // 1.2 s instead of 2 s for a million points.
    using SortTraits =
        CGAL::Spatial_sort_traits_adapter_2<Kernel, CGAL::First_of_pair_property_map<IndexedPoint>>;
    CGAL::spatial_sort(input.begin(), input.end(), SortTraits());
    Delaunay::Vertex_handle previous;
    for (const IndexedPoint& point : input) {
      if (ShouldStop()) return false;
      // A repeated position returns the existing vertex; its index is then one
      // of the coincident points, which JudgeCoincidentPoints handles.
      previous =
          dt_.insert(point.first, previous == Delaunay::Vertex_handle() ? Delaunay::Face_handle()
                                                                        : previous->face());
      previous->info() = point.second;
    }
    input = {};

    // One pass over the faces (circumcentres), one over the edges (spacing and
    // Voronoi edges crossing the area's boundary): each is a few tenths of a
    // second per million points, so the scan costs less than the insertion.
    if (!ScanFaces()) return false;
    for (auto e = dt_.finite_edges_begin(); e != dt_.finite_edges_end(); ++e) {
      if (ShouldStop()) return false;
      const Delaunay::Face_handle f = e->first;
      const int i = e->second;
      JudgePair(lifted_[f->vertex(Delaunay::cw(i))->info()],
                lifted_[f->vertex(Delaunay::ccw(i))->info()]);
      CrossVoronoiEdge(f, i);
    }
    // The triangulation keeps one vertex per position, so coincident input
    // points (distance 0, the worst violation) have no edge: find them apart.
    if (dt_.number_of_vertices() < lifted_.size()) JudgeCoincidentPoints();
    report_.spacing_ok = report_.spacing_violations == 0;
    report_.min_distance = std::sqrt(best_squared_distance_);

    if (dt_.number_of_vertices() == 0) {
      const Rect& area = judging_.area;
      best_radius_ = std::numeric_limits<double>::infinity();
      best_centre_ = {0.5 * (area.x0 + area.x1), 0.5 * (area.y0 + area.y1)};
    }
    report_.largest_empty_circle = best_radius_;
    report_.largest_empty_centre = best_centre_;
    report_.maximal_ok = report_.largest_empty_circle <
                         judging_.min_distance * (1.0 + judging_.options.max_tolerance);
    return true;
  }

 private:
  // True once options.stop asks to stop, polled every 16,384 calls: a poll
  // (an atomic read behind a std::function) then costs nothing measurable.
  bool ShouldStop() {
    return judging_.options.stop && (++steps_ & 0x3FFF) == 0 && judging_.options.stop();
  }

  // Judges the input pair behind an edge once, in the contract's expression.
  void JudgePair(LiftedPoint a, LiftedPoint b) {
    const std::span<const Vec2> points = judging_.points;
    Vec2 position_a = a.position, position_b = b.position;
    double squared = 0.0;
    switch (judging_.pair_rule) {
      case PairRule::kEvery:
        squared = SquaredDistance(position_a, position_b);
        break;
      case PairRule::kTouchesWindow:
        if (!judging_.area.Contains(position_a) && !judging_.area.Contains(position_b)) return;
        squared = SquaredDistance(position_a, position_b);
        break;
      case PairRule::kTorusOnce: {
        // A point and its own image are no pair, even on a torus narrower than d.
        if (a.index == b.index) return;
        if (a.index > b.index) std::swap(a, b);
        // Of the translates of this pair, judge the one whose lower-indexed end
        // is the original: it is present whenever the pair is shorter than the
        // replicated band, and exactly one translate qualifies.
        if (a.shift_x != 0 || a.shift_y != 0) return;
        position_a = points[a.index];
        const Vec2 shift{b.shift_x * judging_.width, b.shift_y * judging_.height};
        position_b = points[b.index] + shift;
        // The sampler that placed the later point measured it against the
        // nearest image of the earlier one; the order is unknown, so take both.
        squared = std::min(SquaredDistance(position_a, position_b),
                           SquaredDistance(points[b.index], position_a - shift));
        break;
      }
    }
    Record(a.index, b.index, position_a, position_b, squared);
  }

  void Record(uint32_t index_a, uint32_t index_b, Vec2 position_a, Vec2 position_b,
              double squared) {
    ++report_.pairs_checked;
    const bool violates = squared < squared_min_distance_;
    report_.spacing_violations += violates;
    if (squared < best_squared_distance_) {
      best_squared_distance_ = squared;
      report_.closest_a = position_a;
      report_.closest_b = position_b;
      report_.closest_index_a = index_a;
      report_.closest_index_b = index_b;
    }
    const double seam = judging_.options.seam_spacing;
    if (seam > 0.0) {
      const Vec2 a = judging_.points[index_a], b = judging_.points[index_b];
      if (std::floor(a.x / seam) != std::floor(b.x / seam) ||
          std::floor(a.y / seam) != std::floor(b.y / seam)) {
        ++report_.pairs_across_seams;
        report_.spacing_violations_across_seams += violates;
        report_.min_distance_across_seams =
            std::min(report_.min_distance_across_seams, std::sqrt(squared));
      }
    }
  }

  // Coincident input points, found by sorting: O(N log N), only when the
  // triangulation reports merged vertices.
  void JudgeCoincidentPoints() {
    const std::span<const Vec2> points = judging_.points;
    std::vector<uint32_t> order(points.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](uint32_t i, uint32_t j) {
      return points[i].x < points[j].x || (points[i].x == points[j].x && points[i].y < points[j].y);
    });
    for (size_t k = 1; k < order.size(); ++k) {
      const Vec2 a = points[order[k - 1]], b = points[order[k]];
      if (!(a == b)) continue;
      if (judging_.pair_rule == PairRule::kTouchesWindow && !judging_.area.Contains(a)) continue;
      Record(order[k - 1], order[k], a, b, 0.0);
    }
  }

  // F1 (distance to the nearest point) at `spot`, measured, not assumed.
  double NearestDistance(Vec2 spot, Delaunay::Face_handle hint) const {
    const Delaunay::Vertex_handle v = dt_.nearest_vertex(CgalPoint(spot.x, spot.y), hint);
    return std::sqrt(SquaredDistance(spot, PositionOf(v)));
  }

  void Consider(double radius, Vec2 centre) {
    if (radius > best_radius_) {
      best_radius_ = radius;
      best_centre_ = centre;
    }
  }

  // F1's maximum over the closed area is at a Voronoi vertex (a circumcentre)
  // inside it, where a Voronoi edge crosses its boundary (CrossVoronoiEdge),
  // or at a corner. Also keeps every face's circumcentre for the edges.
  // False when stopped.
  bool ScanFaces() {
    if (dt_.number_of_vertices() == 0) return true;
    const Rect& area = judging_.area;
    const Delaunay::Face_handle no_hint;
    for (const Vec2 corner : {Vec2{area.x0, area.y0}, Vec2{area.x1, area.y0},
                              Vec2{area.x0, area.y1}, Vec2{area.x1, area.y1}}) {
      Consider(NearestDistance(corner, no_hint), corner);
    }
    centres_.reserve(dt_.number_of_faces());
    for (auto f = dt_.finite_faces_begin(); f != dt_.finite_faces_end(); ++f) {
      if (ShouldStop()) return false;
      f->info() = static_cast<uint32_t>(centres_.size());
      const CgalPoint c = dt_.circumcenter(f);
      const Vec2 centre{c.x(), c.y()};
      centres_.push_back(centre);
      if (!WithinClosed(area, centre, slack_)) continue;
      if (WithinClosed(area, centre, 0.0)) {
        // The circumcircle is empty (exact Delaunay), so F1 there is its radius.
        Consider(std::sqrt(SquaredDistance(centre, PositionOf(f->vertex(0)))), centre);
      } else {
        const Vec2 inside = ClampTo(area, centre);
        Consider(NearestDistance(inside, f), inside);
      }
    }
    return true;
  }

  // Measures F1 where the Voronoi edge dual to edge (f, i) crosses the boundary.
  void CrossVoronoiEdge(Delaunay::Face_handle f, int i) {
    const Vec2 p = PositionOf(f->vertex(Delaunay::cw(i)));
    const Vec2 q = PositionOf(f->vertex(Delaunay::ccw(i)));
    const Vec2 bisector_direction{p.y - q.y, q.x - p.x};
    if (dt_.dimension() < 2) {
      // Collinear points: the dual of an edge is its whole bisector.
      CrossBoundary(0.5 * (p + q), bisector_direction, -kInfinity, kInfinity, f);
      return;
    }
    Delaunay::Face_handle g = f->neighbor(i);
    if (dt_.is_infinite(f)) {
      std::swap(f, g);
      i = f->index(g);
    }
    if (!dt_.is_infinite(g)) {
      const Vec2 c1 = centres_[f->info()], c2 = centres_[g->info()];
      // A Voronoi edge can only cross a side its bounding box reaches.
      if (MayCross(c1, c2)) CrossBoundary(c1, c2 - c1, 0.0, 1.0, f);
    } else {
      // A hull edge: its Voronoi edge is a ray leaving the finite face's
      // circumcentre away from that face's third vertex.
      const Vec2 third = PositionOf(f->vertex(i));
      const Vec2 outward =
          Dot(bisector_direction, third - p) > 0.0 ? -1.0 * bisector_direction : bisector_direction;
      CrossBoundary(centres_[f->info()], outward, 0.0, kInfinity, f);
    }
  }

  bool MayCross(Vec2 c1, Vec2 c2) const {
    const Rect& a = judging_.area;
    const double x_low = std::min(c1.x, c2.x) - slack_, x_high = std::max(c1.x, c2.x) + slack_;
    const double y_low = std::min(c1.y, c2.y) - slack_, y_high = std::max(c1.y, c2.y) + slack_;
    const bool reaches_vertical_side =
        (x_low <= a.x0 && a.x0 <= x_high) || (x_low <= a.x1 && a.x1 <= x_high);
    const bool reaches_horizontal_side =
        (y_low <= a.y0 && a.y0 <= y_high) || (y_low <= a.y1 && a.y1 <= y_high);
    return reaches_vertical_side || reaches_horizontal_side;
  }

  // Where origin + s * direction, s in [s_low, s_high], meets a side of the
  // area, measures F1 there. A piece parallel to a side meets it only at its
  // ends, which are circumcentres or corners, already considered.
  void CrossBoundary(Vec2 origin, Vec2 direction, double s_low, double s_high,
                     Delaunay::Face_handle hint) {
    const double length = Length(direction);
    if (!(length > 0.0)) return;  // a Voronoi edge of length 0 is a vertex
    const double s_slack = slack_ / length;
    const Rect& a = judging_.area;
    const auto cross = [&](double origin_along, double direction_along, double side,
                           double origin_across, double direction_across, double across_low,
                           double across_high, bool vertical) {
      if (std::abs(direction_along) <= 1e-12 * length) return;
      double s = (side - origin_along) / direction_along;
      if (s < s_low - s_slack || s > s_high + s_slack) return;
      s = std::clamp(s, s_low, s_high);
      const double across = origin_across + s * direction_across;
      if (across < across_low - slack_ || across > across_high + slack_) return;
      const double clamped = std::clamp(across, across_low, across_high);
      const Vec2 spot = vertical ? Vec2{side, clamped} : Vec2{clamped, side};
      Consider(NearestDistance(spot, hint), spot);
    };
    for (const double x : {a.x0, a.x1}) {
      cross(origin.x, direction.x, x, origin.y, direction.y, a.y0, a.y1, true);
    }
    for (const double y : {a.y0, a.y1}) {
      cross(origin.y, direction.y, y, origin.x, direction.x, a.x0, a.x1, false);
    }
  }

  static constexpr double kInfinity = std::numeric_limits<double>::infinity();

  const Judging& judging_;
  const std::vector<LiftedPoint>& lifted_;
  VerifyReport& report_;
  Delaunay dt_;
  double squared_min_distance_ = 0.0;
  double slack_ = 0.0;
  double best_squared_distance_ = kInfinity;
  double best_radius_ = -1.0;
  Vec2 best_centre_;
  std::vector<Vec2> centres_;  // per finite face, indexed by its info()
  uint64_t steps_ = 0;         // ShouldStop's calls
};

Status Stopped() { return Cancelled("verify: stopped before the end (its caller has gone)"); }

bool IsFinite(double v) { return std::isfinite(v); }

Status ValidateInputs(std::span<const Vec2> points, const Rect& rect, std::string_view rect_name,
                      double min_distance, const VerifyOptions& options) {
  if (!IsFinite(min_distance) || !(min_distance > 0.0)) {
    return InvalidArgument("min_distance: must be finite and > 0, got " +
                           std::to_string(min_distance));
  }
  if (!IsFinite(rect.x0) || !IsFinite(rect.y0) || !IsFinite(rect.x1) || !IsFinite(rect.y1) ||
      !(rect.x0 < rect.x1) || !(rect.y0 < rect.y1)) {
    return InvalidArgument(std::string(rect_name) +
                           ": must be finite with x0 < x1 and y0 < y1 (non-empty)");
  }
  if (!IsFinite(options.max_tolerance) || options.max_tolerance < 0.0) {
    return InvalidArgument("max_tolerance: must be finite and >= 0");
  }
  if (!IsFinite(options.seam_spacing) || options.seam_spacing < 0.0) {
    return InvalidArgument("seam_spacing: must be finite and >= 0 (0 disables seams)");
  }
  if (points.size() > kMaxVerifiedPoints) {
    return InvalidArgument("points: at most " + std::to_string(kMaxVerifiedPoints) + ", got " +
                           std::to_string(points.size()));
  }
  for (size_t i = 0; i < points.size(); ++i) {
    if (!IsFinite(points[i].x) || !IsFinite(points[i].y)) {
      return InvalidArgument("points[" + std::to_string(i) + "]: coordinates must be finite");
    }
  }
  return Status::Ok();
}

std::vector<LiftedPoint> Unshifted(std::span<const Vec2> points) {
  std::vector<LiftedPoint> lifted(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    lifted[i] = {points[i], static_cast<uint32_t>(i), 0, 0};
  }
  return lifted;
}

// Input points plus their translates that fall within `band` of the rectangle.
std::vector<LiftedPoint> LiftToTorus(std::span<const Vec2> points, const Rect& rect, double band) {
  std::vector<LiftedPoint> lifted = Unshifted(points);
  const Rect grown{rect.x0 - band, rect.y0 - band, rect.x1 + band, rect.y1 + band};
  for (size_t i = 0; i < points.size(); ++i) {
    for (int sy = -1; sy <= 1; ++sy) {
      for (int sx = -1; sx <= 1; ++sx) {
        if (sx == 0 && sy == 0) continue;
        // The same sum a sampler's nearest-image computation makes: q + k * W.
        const Vec2 image{points[i].x + sx * rect.Width(), points[i].y + sy * rect.Height()};
        if (WithinClosed(grown, image, 0.0)) {
          lifted.push_back(
              {image, static_cast<uint32_t>(i), static_cast<int8_t>(sx), static_cast<int8_t>(sy)});
        }
      }
    }
  }
  return lifted;
}

}  // namespace

StatusOr<VerifyReport> VerifyDomain(std::span<const Vec2> points, const Domain& domain,
                                    double min_distance, const VerifyOptions& options) {
  if (Status s = ValidateInputs(points, domain.rect, "domain.rect", min_distance, options);
      !s.ok()) {
    return s;
  }
  Judging judging{points,
                  domain.rect,
                  domain.torus ? PairRule::kTorusOnce : PairRule::kEvery,
                  domain.rect.Width(),
                  domain.rect.Height(),
                  min_distance,
                  options};
  int64_t inside = 0;
  for (const Vec2& p : points) inside += domain.rect.Contains(p);

  VerifyReport report;
  if (!domain.torus) {
    const std::vector<LiftedPoint> lifted = Unshifted(points);
    if (!Scan(judging, lifted, report).Run()) return Stopped();
  } else {
    // F1 of the replicated set equals the torus's F1 wherever it is below the
    // band (a missing image is farther than the band), so a radius below the
    // band is exact; otherwise widen the band, at last to every image.
    const double every_image = std::max(domain.rect.Width(), domain.rect.Height());
    for (double band = 2.0 * min_distance;; band *= 2.0) {
      band = std::min(band, every_image);
      report = VerifyReport{};
      const std::vector<LiftedPoint> lifted = LiftToTorus(points, domain.rect, band);
      if (!Scan(judging, lifted, report).Run()) return Stopped();
      if (report.largest_empty_circle < band || band >= every_image) break;
    }
  }
  report.points_checked = inside;
  report.points_outside = static_cast<int64_t>(points.size()) - inside;
  return report;
}

StatusOr<VerifyReport> VerifyWindow(std::span<const Vec2> points, const Rect& window,
                                    double min_distance, const VerifyOptions& options) {
  if (Status s = ValidateInputs(points, window, "window", min_distance, options); !s.ok()) {
    return s;
  }
  const Judging judging{points, window, PairRule::kTouchesWindow, 0.0, 0.0, min_distance, options};
  VerifyReport report;
  const std::vector<LiftedPoint> lifted = Unshifted(points);
  if (!Scan(judging, lifted, report).Run()) return Stopped();
  for (const Vec2& p : points) report.points_checked += window.Contains(p);
  return report;
}

}  // namespace scallop
