// SampleField: growth along each point's spacing curve (A3's boundary with R from the field),
// then a sweep of cells that certifies coverage with interval bounds of R, seeding whatever the
// growth did not reach (mask components, gaps left between curve tries).
#include "scallop/sampling/field_sampler.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "scallop/field/field_evaluator.h"
#include "scallop/geometry/rect_tiles.h"
#include "scallop/random/rng.h"
#include "scallop/sampling/field_point_grid.h"
#include "scallop/sampling/sampling_problem.h"

namespace scallop {
namespace {

constexpr double kTwoPi = 6.283185307179586;

class FieldRun {
 public:
  // `problem` (optional): a plane region's fixed and inert points, closed rectangles and stop
  // rectangle; its domain must be `domain`.
  FieldRun(const Rect& domain, const RadiusField& field, Rng rng, int curve_tries,
           FieldSampleStats* stats, const SamplingProblem* problem = nullptr)
      : rect_(domain),
        field_(field),
        evaluator_(field),
        rng_(rng),
        grid_(problem == nullptr ? rect_ : Grown(rect_, 2.0 * field.r_max()), GridCell(field)),
        tries_(curve_tries),
        slope_(field.Slope()),
        stats_(stats),
        problem_(problem),
        exclusions_(ExclusionArea(domain, problem), ExclusionCell(field, problem)) {
    const double m =
        std::max({std::abs(rect_.x0), std::abs(rect_.x1), std::abs(rect_.y0), std::abs(rect_.y1)}) +
        field.r_max();
    pad_absolute_ = 8.0 * (std::nextafter(m, INFINITY) - m);
    reach_factor_ = (1.0 / (1.0 - slope_)) * (1.0 + 1e-9);
    if (problem != nullptr && problem->stop_when_covered) stop_ = *problem->stop_when_covered;
    if (problem != nullptr) {
      for (const ExclusionDisk& disk : problem->exclusions) {
        if (!(disk.radius > 0.0)) continue;  // a distance of 0 excludes nothing
        exclusions_.Add(disk.centre, disk.radius);
        largest_exclusion_ = std::max(largest_exclusion_, disk.radius);
      }
    }
  }

  std::vector<Vec2> Run() {
    // One uniform seed, so that the growth's order, not the sweep's, shapes the bulk.
    for (int k = 0; k < 64; ++k) {
      const Vec2 x{rng_.Uniform(rect_.x0, rect_.x1), rng_.Uniform(rect_.y0, rect_.y1)};
      if (TryPlace(x)) {
        Grow();
        break;
      }
    }
    Sweep(rect_);
    std::vector<Vec2> out;
    out.reserve(grid_.points().size());
    for (const FieldPoint& q : grid_.points()) out.push_back(q.p);
    return out;
  }

  // The stream after the run, for a caller that goes on drawing from it.
  const Rng& rng() const { return rng_; }

  // A plane region's run (SampleFieldProblem): the inert points constrain, the fixed points
  // constrain and are the first candidates, a seed from seed_area starts the growth when no
  // fixed point is near enough to seed the domain; only candidates whose curve may reach the
  // stop rectangle are processed, and the sweep certifies that rectangle (or the domain).
  std::vector<Vec2> RunProblem(std::vector<bool>* unprocessed) {
    const SamplingProblem& problem = *problem_;
    for (const Vec2& p : problem.inert_points) grid_.Add(p, Radius(p));
    for (const Vec2& p : problem.fixed_points) Place(p, Radius(p));
    const auto fixed_count = static_cast<int32_t>(grid_.points().size());
    const double seed_reach = field_.r_max() * reach_factor_;
    if (NeedsSeedPoint(problem, seed_reach)) {
      for (int k = 0; k < 64; ++k) {
        if (TryPlace(SeedPoint(problem, rng_))) break;
      }
    }
    Grow();
    Sweep(stop_ ? *stop_ : rect_);
    const std::vector<FieldPoint>& all = grid_.points();
    if (unprocessed != nullptr) {
      unprocessed->assign(all.size() - static_cast<size_t>(fixed_count), false);
      for (const std::vector<int32_t>* left : {&queue_, &beyond_stop_}) {
        for (const int32_t index : *left) {
          if (index >= fixed_count) {
            (*unprocessed)[static_cast<size_t>(index - fixed_count)] = true;
          }
        }
      }
    }
    std::vector<Vec2> out;
    out.reserve(all.size() - static_cast<size_t>(fixed_count));
    for (size_t k = static_cast<size_t>(fixed_count); k < all.size(); ++k) out.push_back(all[k].p);
    return out;
  }

 private:
  // sqrt(r_min r_max): a dense query scans ~9 cells, a sparse one ~(2 sqrt(ratio))^2 mostly
  // empty cells; the geometric mean balances the two.
  static double GridCell(const RadiusField& field) {
    return std::sqrt(field.r_min() * field.r_max());
  }

  // The exclusion disks are filed like points, over the domain grown by the largest of them,
  // in cells no smaller than that radius (a disk test then scans at most 4 cells) nor than the
  // points' cells (so that tiny distances do not make a huge grid).
  static double LargestExclusion(const SamplingProblem* problem) {
    double largest = 0.0;
    if (problem != nullptr) {
      for (const ExclusionDisk& disk : problem->exclusions)
        largest = std::max(largest, disk.radius);
    }
    return largest;
  }
  static Rect ExclusionArea(const Rect& domain, const SamplingProblem* problem) {
    return Grown(domain, LargestExclusion(problem));
  }
  static double ExclusionCell(const RadiusField& field, const SamplingProblem* problem) {
    return std::max(LargestExclusion(problem), GridCell(field));
  }

  // True when x lies strictly inside an exclusion disk (dx^2 + dy^2 < D^2 in doubles).
  bool Excluded(Vec2 x) const {
    if (largest_exclusion_ == 0.0) return false;
    return exclusions_.AnyNear(Grown(Rect{x.x, x.y, x.x, x.y}, largest_exclusion_),
                               [&](const FieldPoint& c) {
                                 const double dx = x.x - c.p.x;
                                 const double dy = x.y - c.p.y;
                                 return dx * dx + dy * dy < c.r * c.r;
                               });
  }

  // True when one exclusion disk holds the whole closed cell: its farthest corner is closer
  // than the disk's radius, with the coverage test's 1e-9 relative margin for rounding.
  bool InOneExclusion(const Rect& c) const {
    if (largest_exclusion_ == 0.0) return false;
    const Vec2 centre{0.5 * (c.x0 + c.x1), 0.5 * (c.y0 + c.y1)};
    return exclusions_.AnyNear(
        Grown(Rect{centre.x, centre.y, centre.x, centre.y}, largest_exclusion_),
        [&](const FieldPoint& e) {
          const double dx = std::max(e.p.x - c.x0, c.x1 - e.p.x);
          const double dy = std::max(e.p.y - c.y0, c.y1 - e.p.y);
          return (dx * dx + dy * dy) * (1.0 + 1e-9) < e.r * e.r;
        });
  }

  // A cell that no single disk holds, but that the points' conflict disks and the exclusion
  // disks hold together (along an exclusion's edge, say): certified when
  // H(centre) + (1 + L) half-diagonal < 0, with H(x) = min(G(x), E(x)), G as in the verifier
  // and E(x) = min_c |x - c| - D_c. Both have slope <= 1 + L, so H < 0 on the whole cell. H
  // is taken over the points and disks within r_max (or the largest D) of the centre: fewer
  // can only raise it, which keeps the certificate sound.
  bool CoveredOrExcludedByBound(const Rect& c) {
    const Vec2 centre{0.5 * (c.x0 + c.x1), 0.5 * (c.y0 + c.y1)};
    const double half_diagonal = 0.5 * std::sqrt(c.Width() * c.Width() + c.Height() * c.Height());
    const double rx = Radius(centre);
    double h = std::numeric_limits<double>::infinity();
    const Rect near = Grown(Rect{centre.x, centre.y, centre.x, centre.y}, field_.r_max());
    grid_.AnyNear(near, [&](const FieldPoint& q) {
      h = std::min(h, std::sqrt(SquaredDistance(centre, q.p)) - std::max(rx, q.r));
      return false;
    });
    exclusions_.AnyNear(Grown(Rect{centre.x, centre.y, centre.x, centre.y}, largest_exclusion_),
                        [&](const FieldPoint& e) {
                          h = std::min(h, std::sqrt(SquaredDistance(centre, e.p)) - e.r);
                          return false;
                        });
    return h + (1.0 + slope_) * half_diagonal * (1.0 + 1e-9) + 1e-12 * field_.r_max() < 0.0;
  }

  // The radius, padded so that a point placed at it from p stays at least R apart in doubles
  // after its coordinates are rounded (as SpacingFor does for a constant d).
  double Pad(double t) const { return t * (1.0 + 0x1.0p-32) + pad_absolute_; }

  // Beyond this no point can be in conflict with a spot of radius rx: |x - q| < R(q) <=
  // rx + L |x - q| gives |x - q| < rx / (1 - L); never more than r_max.
  double Reach(double rx) const { return std::min(field_.r_max(), rx * reach_factor_); }

  double Radius(Vec2 x) const {
    if (stats_ != nullptr) ++stats_->evaluations;
    return evaluator_.Evaluate(x);
  }

  // Where a new point may go: the domain, outside masks and the problem's closed rectangles.
  bool Open(Vec2 x) const {
    return rect_.Contains(x) && !field_.IsMasked(x) &&
           (problem_ == nullptr || !InCoveredRect(*problem_, x)) && !Excluded(x);
  }

  bool Admissible(Vec2 x, double rx) const { return Open(x) && !Conflicts(x, rx); }

  bool TryPlace(Vec2 x) {
    if (!Open(x)) return false;
    const double rx = Radius(x);
    if (Conflicts(x, rx)) return false;
    Place(x, rx);
    return true;
  }

  // Whether a candidate's curve may reach the stop rectangle: its spots lie within
  // Pad(R(p) / (1 - L)) of p.
  bool ReachesStop(const FieldPoint& p) const {
    if (!stop_) return false;
    const double limit = Pad(p.r * reach_factor_);
    return SquaredDistance(*stop_, p.p) < limit * limit;
  }

  void Place(Vec2 x, double rx) {
    const auto index = static_cast<int32_t>(grid_.points().size());
    (!stop_ || ReachesStop({x, rx}) ? queue_ : beyond_stop_).push_back(index);
    grid_.Add(x, rx);
  }

  // True when every spot of p + t u, t in [t_lo, t_hi], lies inside some point's own disk
  // D(q, R(q)), hence in conflict with q whatever R is there: the try can be skipped without
  // evaluating the field. Looks at the candidate's gathered neighbours only; a shortcut, never
  // needed for exactness.
  bool SegmentInOneDisk(const FieldPoint& p, Vec2 u, double t_lo, double t_hi) const {
    const Vec2 a{p.p.x + t_lo * u.x, p.p.y + t_lo * u.y};
    const Vec2 b{p.p.x + t_hi * u.x, p.p.y + t_hi * u.y};
    for (const std::vector<FieldPoint>* disks : {&near_, &near_exclusions_}) {
      for (const FieldPoint& q : *disks) {
        const double r2 = q.r * q.r;
        if (SquaredDistance(a, q.p) < r2 && SquaredDistance(b, q.p) < r2) return true;
      }
    }
    return false;
  }

  // Every point that can conflict with a spot of p's curve: spots lie within
  // s_max = Pad(R(p) / (1 - L)) of p and have R <= s_max. Gathered once per candidate, so that
  // its tries scan one short array instead of the grid's cells.
  void GatherNear(const FieldPoint& p) {
    spot_limit_ = Pad(p.r * reach_factor_);
    const double s = spot_limit_;
    near_.clear();
    // A spot x of the curve is within s of p and has R(x) <= s, so a point q can conflict with
    // it only if |x - q| < max(s, R(q)), i.e. |p - q| < s + max(s, R(q)); and q's own disk can
    // hold a whole bracket only if |p - q| < s + R(q). No such q is farther than s + Reach(s).
    // (1e-9: the doubles' tests of the spot may pass a point a few ulp farther.)
    const auto reach = [s](double r) { return (s + std::max(s, r)) * (1.0 + 1e-9); };
    grid_.AnyNear(Grown(Rect{p.p.x, p.p.y, p.p.x, p.p.y}, s + Reach(s)), [&](const FieldPoint& q) {
      const double m = reach(q.r);
      if (SquaredDistance(p.p, q.p) < m * m) near_.push_back(q);
      return false;
    });
    // The exclusion disks that meet the curve's reach: a try inside one is skipped unevaluated.
    near_exclusions_.clear();
    if (largest_exclusion_ == 0.0) return;
    exclusions_.AnyNear(Grown(Rect{p.p.x, p.p.y, p.p.x, p.p.y}, spot_limit_ + largest_exclusion_),
                        [&](const FieldPoint& e) {
                          // 1e-9 more: a disk that holds a spot within spot_limit_ of p must be
                          // listed whatever the rounding of these sums.
                          const double reach = (spot_limit_ + e.r) * (1.0 + 1e-9);
                          if (SquaredDistance(p.p, e.p) < reach * reach)
                            near_exclusions_.push_back(e);
                          return false;
                        });
  }

  // Admissible against the gathered points when the spot is within the gathered range (always,
  // unless the root search stopped outside its bracket), else against the grid.
  bool AdmissibleNear(const FieldPoint& p, Vec2 x, double rx) const {
    if (!(rx <= spot_limit_ && SquaredDistance(p.p, x) <= spot_limit_ * spot_limit_)) {
      return Admissible(x, rx);
    }
    // Open(x), with the exclusion disks from the gathered list: it holds every disk that can
    // hold a spot within spot_limit_ of p.
    if (!rect_.Contains(x) || field_.IsMasked(x) ||
        (problem_ != nullptr && InCoveredRect(*problem_, x))) {
      return false;
    }
    for (const FieldPoint& e : near_exclusions_) {
      const double dx = x.x - e.p.x;
      const double dy = x.y - e.p.y;
      if (dx * dx + dy * dy < e.r * e.r) return false;
    }
    for (const FieldPoint& q : near_) {
      const double dx = x.x - q.p.x;
      const double dy = x.y - q.p.y;
      const double m = std::max(rx, q.r);
      if (dx * dx + dy * dy < m * m) return false;
    }
    return true;
  }

  // The spot along direction u at the spacing p's curve asks for: t = max(R(p), t*) with t* the
  // one root of t - R(p + t u) (slope in [1 - L, 1 + L], so t* <= R(p) / (1 - L)), found by
  // secant steps kept inside the slope's bracket, padded. Returns false when the spot is
  // surely in conflict (the bracket lies in one disk); else the spot and R there, which the
  // caller checks in doubles.
  bool CurveSpot(const FieldPoint& p, Vec2 u, Vec2* x, double* rx) const {
    double t = p.r;
    if (SegmentInOneDisk(p, u, Pad(t), Pad(t * reach_factor_))) return false;
    double previous_t = 0.0;
    double previous_f = 0.0;
    for (int iteration = 0;; ++iteration) {
      const double s = Pad(t);
      *x = Vec2{p.p.x + s * u.x, p.p.y + s * u.y};
      *rx = Radius(*x);
      const double f = s - *rx;
      if (f >= 0.0 || iteration == 5) return true;
      double step = iteration == 0 ? -f : -f * (t - previous_t) / (f - previous_f);
      const double lo = -f / (1.0 + slope_);
      const double hi = -f / (1.0 - slope_);
      if (iteration == 0 && SegmentInOneDisk(p, u, Pad(t + lo), Pad(t + hi))) return false;
      step = iteration >= 3 ? hi : std::clamp(step, lo, hi);
      previous_t = t;
      previous_f = f;
      t += step;
    }
  }

  // Takes candidates uniformly until none is left; with a stop rectangle, only those whose
  // curve can reach it (the sweep then certifies the rectangle).
  void Grow() {
    while (!queue_.empty()) {
      const size_t k = rng_.Below(queue_.size());
      const int32_t index = queue_[k];
      queue_[k] = queue_.back();
      queue_.pop_back();
      const double start = kTwoPi * rng_.Uniform();
      const double step = kTwoPi / tries_;
      const FieldPoint p = grid_.points()[static_cast<size_t>(index)];
      GatherNear(p);
      for (int j = 0; j < tries_; ++j) {
        Vec2 x;
        double rx;
        if (stats_ != nullptr) ++stats_->curve_spots;
        if (CurveSpot(p, UnitAt(start + step * j), &x, &rx) && AdmissibleNear(p, x, rx)) {
          Place(x, rx);
          near_.push_back({x, rx});
          if (stats_ != nullptr) ++stats_->grown;
        }
      }
    }
  }

  // A cell is covered when one point's conflict disk holds it whole: its farthest corner is
  // closer than max(R(q), lower bound of R over the cell). Every spot of it is then in conflict
  // with q. The 1e-9 relative margin absorbs the rounding of the corner distances.
  // A coverer's farthest corner is closer than R_hi / (1 - L) (see Certify), and the centre,
  // the corners' mean, is no farther from q than that corner: so q lies within that reach of
  // the centre. The grid cell holding the centre is looked at first, where a coverer usually is.
  bool CoveredByOnePoint(const Rect& c, double r_low, double r_high) const {
    const double reach = std::min(field_.r_max(), r_high * reach_factor_);
    const auto covers = [&](const FieldPoint& q) {
      const double dx = std::max(q.p.x - c.x0, c.x1 - q.p.x);
      const double dy = std::max(q.p.y - c.y0, c.y1 - q.p.y);
      const double m = std::max(q.r, r_low);
      return (dx * dx + dy * dy) * (1.0 + 1e-9) < m * m;
    };
    if (sweep_hint_ && covers(*sweep_hint_)) return true;
    const auto remember = [&](const FieldPoint& q) {
      if (!covers(q)) return false;
      sweep_hint_ = q;
      return true;
    };
    const Rect centre{0.5 * (c.x0 + c.x1), 0.5 * (c.y0 + c.y1), 0.5 * (c.x0 + c.x1),
                      0.5 * (c.y0 + c.y1)};
    return grid_.AnyNear(centre, remember) || grid_.AnyNear(Grown(centre, reach), remember);
  }

  // Whether x (with R(x) = rx) conflicts with some point: the sweep's hint first, then the grid.
  bool Conflicts(Vec2 x, double rx) const {
    if (sweep_hint_) {
      const double dx = x.x - sweep_hint_->p.x;
      const double dy = x.y - sweep_hint_->p.y;
      const double m = std::max(rx, sweep_hint_->r);
      if (dx * dx + dy * dy < m * m) return true;
    }
    return grid_.Conflicts(x, rx, Reach(rx));
  }

  // The spot nearest to x inside the half-open domain (x itself unless on a top or right edge).
  Vec2 Inside(Vec2 x) const {
    if (x.x >= rect_.x1) x.x = std::nextafter(rect_.x1, rect_.x0);
    if (x.y >= rect_.y1) x.y = std::nextafter(rect_.y1, rect_.y0);
    return x;
  }

  void Certify(const Rect& c, int depth) {
    for (;;) {
      if (field_.HasMask() && field_.AllMasked(c)) return;
      if (InOneExclusion(c)) return;
      if (stats_ != nullptr) ++stats_->cells_tested;
      if (stats_ != nullptr) ++stats_->evaluations;
      const RadiusInterval bounds = evaluator_.Bounds(c);
      // One point covers the cell only if its farthest corner, at least half a diagonal away,
      // is closer than R(q) <= R(centre) + L |q - centre|, i.e. closer than R_hi / (1 - L).
      // A cell too large for that is split at once: its children test and dart themselves.
      const double half_diagonal = 0.5 * std::sqrt(c.Width() * c.Width() + c.Height() * c.Height());
      if (depth < max_depth_ &&
          half_diagonal >= std::min(field_.r_max(), bounds.hi * reach_factor_)) {
        break;
      }
      if (CoveredByOnePoint(c, bounds.lo, bounds.hi)) return;
      if (largest_exclusion_ > 0.0 && CoveredOrExcludedByBound(c)) return;
      const Vec2 centre{0.5 * (c.x0 + c.x1), 0.5 * (c.y0 + c.y1)};
      if (depth >= max_depth_) {
        // Finest cell: its centre and quarter points, all inside it (a leaf's inside is wholly
        // unmasked or wholly masked, since partly masked cells were cut at pixel lines). Once
        // each is covered (or excluded), every spot of the cell is within its diagonal of such a
        // spot, and G(x) = min_q |x - q| - max(R(x), R(q)), or with exclusions min(G, E), has
        // slope <= 1 + L: G <= (1 + L) diagonal.
        if (stats_ != nullptr) ++stats_->leaves;
        const double qx0 = c.x0 + 0.25 * (c.x1 - c.x0);
        const double qx1 = c.x0 + 0.75 * (c.x1 - c.x0);
        const double qy0 = c.y0 + 0.25 * (c.y1 - c.y0);
        const double qy1 = c.y0 + 0.75 * (c.y1 - c.y0);
        const Vec2 spots[5] = {centre, {qx0, qy0}, {qx1, qy0}, {qx0, qy1}, {qx1, qy1}};
        for (const Vec2& s : spots) {
          if (TryPlace(Inside(s))) {
            if (stats_ != nullptr) ++stats_->swept;
            Grow();
          }
        }
        return;
      }
      // Not certified: a free spot seeds growth (a dart, then the centre), else split.
      const Vec2 dart{rng_.Uniform(c.x0, c.x1), rng_.Uniform(c.y0, c.y1)};
      if (TryPlace(dart) || TryPlace(Inside(centre))) {
        if (stats_ != nullptr) ++stats_->swept;
        Grow();
        continue;
      }
      break;
    }
    // A partly masked cell is cut along pixel lines first: its masked part is never covered,
    // and halving alone would follow the mask's edge down to the finest cells.
    if (field_.HasMask() && field_.AnyMasked(c)) {
      Rect pieces[4];
      const int n = field_.CutAtPixelLines(c, pieces);
      if (n > 0) {
        for (int k = 0; k < n; ++k) Certify(pieces[k], depth);
        return;
      }
    }
    const double mx = 0.5 * (c.x0 + c.x1);
    const double my = 0.5 * (c.y0 + c.y1);
    Certify({c.x0, c.y0, mx, my}, depth + 1);
    Certify({mx, c.y0, c.x1, my}, depth + 1);
    Certify({c.x0, my, mx, c.y1}, depth + 1);
    Certify({mx, my, c.x1, c.y1}, depth + 1);
  }

  // Base cells of side r_max / 2 (diagonal 0.71 r_max, so a point can cover one whole) in rows
  // from the bottom; depth grows until the side is below 2^-30 r_min.
  void Sweep(const Rect& area) {
    const double base = 0.5 * field_.r_max();
    max_depth_ = 0;
    for (double side = base; side > field_.r_min() * kFieldLeafFraction; side *= 0.5) {
      ++max_depth_;
    }
    ForEachTile(area, base, [&](const Rect& tile) { Certify(tile, 0); });
  }

  Rect rect_;
  const RadiusField& field_;
  // A cache of lattice cells: evaluating through it gives Evaluate's bits, so the const methods
  // that evaluate stay pure.
  mutable FieldEvaluator evaluator_;
  Rng rng_;
  FieldPointGrid grid_;
  int tries_;
  double slope_;
  FieldSampleStats* stats_;
  const SamplingProblem* problem_;
  // The problem's exclusion disks (radius in FieldPoint::r), and the largest radius (0: none).
  FieldPointGrid exclusions_;
  double largest_exclusion_ = 0.0;
  std::optional<Rect> stop_;
  double pad_absolute_ = 0.0;
  double reach_factor_ = 1.0;
  int max_depth_ = 0;
  // Candidates not processed yet. With a stop rectangle, queue_ holds those whose curve may
  // reach it and beyond_stop_ the others, which are never processed: they are the run's
  // growth front, left for the next region to continue.
  std::vector<int32_t> queue_;
  std::vector<int32_t> beyond_stop_;
  // The current candidate's neighbours (GatherNear) and how far its curve's spots reach.
  std::vector<FieldPoint> near_;
  std::vector<FieldPoint> near_exclusions_;
  double spot_limit_ = 0.0;
  // The point that last covered a sweep cell: the next cell, a neighbour, is often covered by
  // it, and a spot there in conflict with it. Any point of the run answers either question
  // truly, so asking it first changes no result.
  mutable std::optional<FieldPoint> sweep_hint_;
};

}  // namespace

Status ValidateFieldSamplerOptions(const FieldSamplerOptions& options, const RadiusField& field) {
  const Rect& r = options.domain;
  if (!std::isfinite(r.x0) || !std::isfinite(r.y0) || !std::isfinite(r.x1) ||
      !std::isfinite(r.y1) || !(r.x0 < r.x1) || !(r.y0 < r.y1)) {
    return InvalidArgument("domain must be a finite rectangle with x0 < x1 and y0 < y1");
  }
  const double limit = kMaxFieldCoordinate * field.r_min();
  if (std::max({std::abs(r.x0), std::abs(r.x1), std::abs(r.y0), std::abs(r.y1)}) > limit) {
    return OutOfRange("domain coordinates must be within 2^32 field.r_min of the origin");
  }
  if (!(FieldDomainCells(r, field.r_min()) <= kMaxFieldDomainCells)) {
    return InvalidArgument(
        "domain (width / field.r_min + 2) * (height / field.r_min + 2) must be at most 6.4e7");
  }
  if (options.curve_tries < 1 || options.curve_tries > 64) {
    return InvalidArgument("curve_tries must be in [1, 64]");
  }
  return Status::Ok();
}

StatusOr<std::vector<Vec2>> SampleField(const FieldSamplerOptions& options,
                                        const RadiusField& field, FieldSampleStats* stats) {
  if (Status s = ValidateFieldSamplerOptions(options, field); !s.ok()) return s;
  return FieldRun(options.domain, field, Rng(HashWords({options.seed, 0x4649454c44ULL})),
                  options.curve_tries, stats)
      .Run();
}

std::vector<Vec2> SampleFieldProblem(const SamplingProblem& problem, const RadiusField& field,
                                     Rng& rng, std::vector<bool>* unprocessed,
                                     FieldSampleStats* stats) {
  FieldRun run(problem.domain.rect, field, rng, FieldSamplerOptions{}.curve_tries, stats, &problem);
  std::vector<Vec2> placed = run.RunProblem(unprocessed);
  rng = run.rng();
  return placed;
}

}  // namespace scallop
