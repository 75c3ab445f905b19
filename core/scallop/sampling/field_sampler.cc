// SampleField: growth along each point's spacing curve (A3's boundary with R from the field),
// then a sweep of cells that certifies coverage with interval bounds of R, seeding whatever the
// growth did not reach (mask components, gaps left between curve tries).
#include "scallop/sampling/field_sampler.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include "scallop/field/field_evaluator.h"
#include "scallop/geometry/rect_tiles.h"
#include "scallop/random/rng.h"
#include "scallop/sampling/available_boundary.h"
#include "scallop/sampling/curve_arcs.h"
#include "scallop/sampling/field_candidate_boundary.h"
#include "scallop/sampling/field_point_grid.h"
#include "scallop/sampling/sampling_problem.h"

namespace scallop {
namespace {

// Half the width, in keys (a whole turn is 4), of what a try always cuts about its own
// direction: 1/128 of a key, 0.7 degrees.
constexpr double kRefusedKeyHalfWidth = 1.0 / 128.0;
// The sweep tests a cell for one coverer only when its half-diagonal is below this times the
// cell's R_hi, and darts in it only below kSweepDartFactor R_lo: larger cells are split untested.
constexpr double kSweepSplitFactor = 0.5;
constexpr double kSweepDartFactor = 0.2;
// The sweep's last coverers, asked first: neighbouring cells are mostly covered by the same
// few points.
constexpr size_t kSweepHints = 8;
// How far from a candidate, in R(p), the growth looks for the disks that cut its circle.
constexpr double kArcWindow = 2.5;
// Points before the grid is first packed: below that, its lists are short and in cache.
constexpr size_t kFirstPack = 4096;

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
    // Packed whenever the points have doubled: each point is copied about twice in all, and
    // most of a search's points are read from packed cells.
    if (grid_.points().size() >= 2 * grid_.packed_count() + kFirstPack) grid_.Pack();
  }

  // Why a spot of a candidate's curve was refused, so that the growth can cut the directions
  // the same cause refuses around it.
  enum class Refusal { kNone, kOutside, kClosed, kDisk };

  // Admissible(x, rx), saying why not; on a refusal by a point or an exclusion disk, *blocker is
  // that disk (its centre and the radius that refused x).
  Refusal Judge(Vec2 x, double rx, FieldPoint* blocker) const {
    if (!rect_.Contains(x)) return Refusal::kOutside;
    if (field_.IsMasked(x) || (problem_ != nullptr && InCoveredRect(*problem_, x))) {
      return Refusal::kClosed;
    }
    const Rect spot{x.x, x.y, x.x, x.y};
    if (largest_exclusion_ > 0.0 &&
        exclusions_.AnyNear(Grown(spot, largest_exclusion_), [&](const FieldPoint& e) {
          const double dx = x.x - e.p.x;
          const double dy = x.y - e.p.y;
          if (!(dx * dx + dy * dy < e.r * e.r)) return false;
          *blocker = e;
          return true;
        })) {
      return Refusal::kDisk;
    }
    const bool conflict = grid_.AnyNear(Grown(spot, Reach(rx)), [&](const FieldPoint& q) {
      const double dx = x.x - q.p.x;
      const double dy = x.y - q.p.y;
      const double m = std::max(rx, q.r);
      if (!(dx * dx + dy * dy < m * m)) return false;
      *blocker = {q.p, m};
      return true;
    });
    return conflict ? Refusal::kDisk : Refusal::kNone;
  }

  // The spot along direction u at the spacing p's curve asks for: t = max(R(p), t*) with t* the
  // one root of t - R(p + t u) (slope in [1 - L, 1 + L], so t* <= R(p) / (1 - L)), found by
  // secant steps kept inside the slope's bracket, padded. Returns the spot and R there, which
  // the caller checks in doubles.
  void CurveSpot(const FieldPoint& p, Vec2 u, Vec2* x, double* rx) const {
    double t = p.r;
    double previous_t = 0.0;
    double previous_f = 0.0;
    for (int iteration = 0;; ++iteration) {
      const double s = Pad(t);
      *x = Vec2{p.p.x + s * u.x, p.p.y + s * u.y};
      *rx = Radius(*x);
      const double f = s - *rx;
      if (f >= 0.0 || iteration == 5) return;
      double step = iteration == 0 ? -f : -f * (t - previous_t) / (f - previous_f);
      const double lo = -f / (1.0 + slope_);
      const double hi = -f / (1.0 - slope_);
      step = iteration >= 3 ? hi : std::clamp(step, lo, hi);
      previous_t = t;
      previous_f = f;
      t += step;
    }
  }

  // Cuts from p's boundary the directions whose spot at distance R(p) lies within the disk of
  // radius m about c. The circle of radius R(p) stands for p's curve, whose spot in a direction
  // is at max(R(p), t*); where the two differ (uphill), a cut may take a free spot, which the
  // sweep finds, or leave one in conflict, which its try refuses: the cut is a guide, never a
  // certificate (every spot is judged in doubles before it becomes a point).
  void CutDiskArc(const FieldPoint& p, Vec2 c, double m) {
    const Vec2 o{c.x - p.p.x, c.y - p.p.y};
    if (o.x == 0.0 && o.y == 0.0) return;
    KeyArc arc;
    Cut(boundary_, DiskArc(o, p.r, m, &arc), arc);
  }

  // The arcs of every point and exclusion disk near p: a point q refuses a spot x of the circle
  // when |x - q| < max(R(x), R(q)), taken as max(R(p), R(q)). Only a q with
  // |p - q| < R(p) + max(R(p), R(q)) meets the circle: within 2 R(p) unless R(q) > R(p). Points
  // are looked for within kArcWindow R(p), which holds those with R(q) up to 1.5 R(p); a farther
  // one whose R is larger still (R(q) <= R(p) + L |p - q| allows up to 2 R(p) / (1 - L)) is
  // found by the try it refuses, which cuts its arc then.
  // By bins (FieldCandidateBoundary): the very ranges that cutting every arc leaves.
  void CutNeighbourArcs(const FieldPoint& p) {
    const Rect at{p.p.x, p.p.y, p.p.x, p.p.y};
    neighbour_arcs_.Start(p.r);
    grid_.AnyNear(Grown(at, kArcWindow * p.r), [&](const FieldPoint& q) {
      const double m = std::max(q.r, p.r);
      const double reach = p.r + m;
      const Vec2 o{q.p.x - p.p.x, q.p.y - p.p.y};
      if (!(SquaredDistance(p.p, q.p) < reach * reach) || (o.x == 0.0 && o.y == 0.0)) {
        return false;
      }
      return neighbour_arcs_.Add(o, m);
    });
    neighbour_arcs_.Finish(boundary_);
    if (largest_exclusion_ == 0.0 || boundary_.empty()) return;
    exclusions_.AnyNear(Grown(at, p.r + largest_exclusion_), [&](const FieldPoint& e) {
      const double reach = p.r + e.r;
      if (SquaredDistance(p.p, e.p) < reach * reach) CutDiskArc(p, e.p, e.r);
      return boundary_.empty();
    });
  }

  // A half-width h (at most t / 2) such that the square of half-side h about x is closed: one
  // covered rectangle holds it, or every spot of it is masked (h from t / 2 down to t / 64);
  // 0 when none is found. O(1) a square with the mask's summed-area table.
  double ClosedAround(Vec2 x, double t) const {
    if (problem_ != nullptr) {
      for (const Rect& r : problem_->covered_rects) {
        if (r.Contains(x)) {
          return std::min(0.5 * t, std::min({x.x - r.x0, r.x1 - x.x, x.y - r.y0, r.y1 - x.y}));
        }
      }
    }
    if (!field_.HasMask()) return 0.0;
    for (double h = 0.5 * t; h >= t / 64.0; h *= 0.5) {
      if (field_.AllMasked(Rect{x.x - h, x.y - h, x.x + h, x.y + h})) return h;
    }
    return 0.0;
  }

  // After a refused try at the spot x (direction key `key`): the directions refused for the same
  // cause on the circle through x, and always a sliver about the key, so that no direction is
  // tried twice.
  void CutRefused(const FieldPoint& p, Vec2 x, double key, Refusal refusal,
                  const FieldPoint& blocker) {
    const Vec2 o{x.x - p.p.x, x.y - p.p.y};
    const double t = std::sqrt(o.x * o.x + o.y * o.y);
    KeyArc arc;
    if (refusal == Refusal::kDisk) {
      Cut(boundary_, DiskArc({blocker.p.x - p.p.x, blocker.p.y - p.p.y}, t, blocker.r, &arc), arc);
    } else if (refusal == Refusal::kClosed) {
      // The spots within `closed` of x are closed too, so are the directions within closed / t
      // radians of x's (a key moves at least as fast as the angle: dkey/dangle is in [1, 2]).
      const double closed = ClosedAround(x, t);
      if (closed > 0.0) CutAroundKey(boundary_, key, std::min(1.0, closed / t));
    } else if (refusal == Refusal::kOutside) {
      const Vec2 normals[4] = {{-1.0, 0.0}, {1.0, 0.0}, {0.0, -1.0}, {0.0, 1.0}};
      const double distances[4] = {p.p.x - rect_.x0, rect_.x1 - p.p.x, p.p.y - rect_.y0,
                                   rect_.y1 - p.p.y};
      for (int k = 0; k < 4; ++k) {
        if (t * t >= distances[k] * distances[k]) {
          Cut(boundary_, BeyondLineArc(normals[k], distances[k], t, &arc), arc);
        }
      }
    }
    CutAroundKey(boundary_, key, kRefusedKeyHalfWidth);
  }

  // Takes candidates uniformly until none is left; with a stop rectangle, only those whose
  // curve can reach it (the sweep then certifies the rectangle). A candidate's boundary starts
  // as its whole curve less the arcs of its neighbours' disks (CutNeighbourArcs); directions are
  // drawn uniformly by angle from what is left, each spot is found on the true curve and checked in
  // doubles, and each try cuts its arc (a new point's disk, or the refusing cause's).
  void Grow() {
    while (!queue_.empty()) {
      const size_t k = rng_.Below(queue_.size());
      const int32_t index = queue_[k];
      queue_[k] = queue_.back();
      queue_.pop_back();
      const FieldPoint p = grid_.points()[static_cast<size_t>(index)];
      CutNeighbourArcs(p);
      for (int j = 0; j < tries_ && !boundary_.empty(); ++j) {
        const AvailableBoundary::Draw draw = boundary_.SampleDirection(rng_);
        const Vec2 u = (1.0 / std::sqrt(SquaredLength(draw.direction))) * draw.direction;
        Vec2 x;
        double rx;
        if (stats_ != nullptr) ++stats_->curve_spots;
        CurveSpot(p, u, &x, &rx);
        FieldPoint blocker;
        const Refusal refusal = Judge(x, rx, &blocker);
        if (refusal == Refusal::kNone) {
          Place(x, rx);
          CutDiskArc(p, x, std::max(rx, p.r));
          CutAroundKey(boundary_, draw.key, kRefusedKeyHalfWidth);
          if (stats_ != nullptr) ++stats_->grown;
        } else {
          CutRefused(p, x, draw.key, refusal, blocker);
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
    // Newest first: the cell just certified is the likeliest neighbour of this one.
    for (size_t j = 1; j <= hint_count_; ++j) {
      if (covers(hints_[(next_hint_ + kSweepHints - j) % kSweepHints])) return true;
    }
    const auto remember = [&](const FieldPoint& q) {
      if (!covers(q)) return false;
      hints_[next_hint_] = q;
      next_hint_ = (next_hint_ + 1) % kSweepHints;
      hint_count_ = std::max(hint_count_, next_hint_);
      if (next_hint_ == 0) hint_count_ = kSweepHints;
      return true;
    };
    const Rect centre{0.5 * (c.x0 + c.x1), 0.5 * (c.y0 + c.y1), 0.5 * (c.x0 + c.x1),
                      0.5 * (c.y0 + c.y1)};
    return grid_.AnyNear(centre, remember) || grid_.AnyNear(Grown(centre, reach), remember);
  }

  // Whether x (with R(x) = rx) conflicts with some point: the sweep's hint first, then the grid.
  bool Conflicts(Vec2 x, double rx) const {
    for (size_t k = 0; k < hint_count_; ++k) {
      const double dx = x.x - hints_[k].p.x;
      const double dy = x.y - hints_[k].p.y;
      const double m = std::max(rx, hints_[k].r);
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

  // `known`: bounds of R over the cell, its parent's; `evaluated`: whether the parent evaluated
  // them (else only known.hi is meaningful). A cell uses an evaluated parent's bounds as its own
  // (looser than its own, still true of it), so only every other level evaluates R.
  void Certify(const Rect& c, int depth, RadiusInterval known, bool evaluated) {
    if (field_.HasMask() && field_.AllMasked(c)) return;
    if (InOneExclusion(c)) return;
    if (stats_ != nullptr) ++stats_->cells_tested;
    const double half_diagonal = 0.5 * std::sqrt(c.Width() * c.Width() + c.Height() * c.Height());
    const bool finest = depth >= max_depth_;
    // One point covers the cell only if its farthest corner, at least half a diagonal away, is
    // closer than R(q) <= R(centre) + L |q - centre|, i.e. closer than R_hi / (1 - L). A cell
    // too large for that is split at once: its children test and dart themselves. So is a cell
    // wider than kSweepSplitFactor R_hi, which one point seldom covers: splitting costs only the
    // children's tests, never a certificate. Any upper bound of R decides it, the parent's too.
    const auto too_large = [&](double hi) {
      return !finest && (half_diagonal >= std::min(field_.r_max(), hi * reach_factor_) ||
                         half_diagonal >= kSweepSplitFactor * hi);
    };
    RadiusInterval bounds = known;
    bool split = too_large(known.hi);
    bool own = false;
    if (!split && !evaluated) {
      if (stats_ != nullptr) ++stats_->evaluations;
      bounds = evaluator_.Bounds(c);
      own = true;
      split = too_large(bounds.hi);
    }
    if (!split && Uncovered(c, half_diagonal, bounds, finest)) split = true;
    if (!split) return;
    // A partly masked cell is cut along pixel lines first: its masked part is never covered,
    // and halving alone would follow the mask's edge down to the finest cells.
    if (field_.HasMask() && field_.AnyMasked(c)) {
      Rect pieces[4];
      const int n = field_.CutAtPixelLines(c, pieces);
      if (n > 0) {
        for (int k = 0; k < n; ++k) Certify(pieces[k], depth, bounds, own);
        return;
      }
    }
    const double mx = 0.5 * (c.x0 + c.x1);
    const double my = 0.5 * (c.y0 + c.y1);
    Certify({c.x0, c.y0, mx, my}, depth + 1, bounds, own);
    Certify({mx, c.y0, c.x1, my}, depth + 1, bounds, own);
    Certify({c.x0, my, mx, c.y1}, depth + 1, bounds, own);
    Certify({mx, my, c.x1, c.y1}, depth + 1, bounds, own);
  }

  // Tests the cell against its coverers (seeding growth from a free spot first when it finds
  // one): false when certified (or, finest, settled by its five spots), true when it must split.
  bool Uncovered(const Rect& c, double half_diagonal, const RadiusInterval& bounds, bool finest) {
    for (;;) {
      if (CoveredByOnePoint(c, bounds.lo, bounds.hi)) return false;
      if (largest_exclusion_ > 0.0 && CoveredOrExcludedByBound(c)) return false;
      const Vec2 centre{0.5 * (c.x0 + c.x1), 0.5 * (c.y0 + c.y1)};
      if (finest) {
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
        return false;
      }
      // Not certified: a free spot seeds growth (a dart, then the centre), else split. Only in
      // cells well below the spacing: in larger ones a free spot is rare, and their children,
      // down to the finest, dart in turn.
      if (half_diagonal >= kSweepDartFactor * bounds.lo) return true;
      const Vec2 dart{rng_.Uniform(c.x0, c.x1), rng_.Uniform(c.y0, c.y1)};
      if (!TryPlace(dart) && !TryPlace(Inside(centre))) return true;
      if (stats_ != nullptr) ++stats_->swept;
      Grow();
    }
  }

  // Base cells of side r_max / 2 (diagonal 0.71 r_max, so a point can cover one whole) in rows
  // from the bottom; depth grows until the side is below 2^-30 r_min.
  void Sweep(const Rect& area) {
    grid_.Pack();
    const double base = 0.5 * field_.r_max();
    max_depth_ = 0;
    for (double side = base; side > field_.r_min() * kFieldLeafFraction; side *= 0.5) {
      ++max_depth_;
    }
    ForEachTile(area, base, [&](const Rect& tile) {
      Certify(tile, 0, {field_.r_min(), field_.r_max()}, false);
    });
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
  // The current candidate's directions left to try.
  AvailableBoundary boundary_;
  // CutNeighbourArcs' builder, kept between candidates for its capacity.
  FieldCandidateBoundary neighbour_arcs_;
  // The points that last covered sweep cells (hints_[0, hint_count_), next_hint_ the oldest): the
  // next cell, a neighbour, is often covered by one of them, and a spot there in conflict with
  // one. Any point of the run answers either question truly, so asking them first changes no
  // result.
  mutable std::array<FieldPoint, kSweepHints> hints_ = {};
  mutable size_t hint_count_ = 0;
  mutable size_t next_hint_ = 0;
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
