// VerifyFieldDomain: pairs through a grid of side r_max, gaps through a certified recursion on
// cells with G's Lipschitz bound. Written apart from the sampler's coverage test (which uses one
// point's disk per cell) so that the two do not share a mistake.
#include "scallop/verify/field_verifier.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "scallop/geometry/rect_tiles.h"
#include "scallop/sampling/field_point_grid.h"
#include "scallop/sampling/field_sampler.h"

namespace scallop {
namespace {

// options.stop, polled every 16,384 steps: a poll may take a lock or read a clock, and a step
// (one point's pairs, one cell) is microseconds, so a stop is noticed within milliseconds.
class StopPoll {
 public:
  explicit StopPoll(const std::function<bool()>& stop) : stop_(stop) {}
  // True once stop has said so (and from then on).
  bool Stopped() {
    if (!stopped_ && stop_ && (++steps_ & 0x3FFF) == 0) stopped_ = stop_();
    return stopped_;
  }

 private:
  const std::function<bool()>& stop_;
  uint64_t steps_ = 0;
  bool stopped_ = false;
};

class GapSearch {
 public:
  GapSearch(const FieldPointGrid& grid, const FieldPointGrid& exclusions, double largest_exclusion,
            const RadiusField& field, double tolerance, FieldVerifyReport* report, StopPoll& poll)
      : grid_(grid),
        exclusions_(exclusions),
        largest_exclusion_(largest_exclusion),
        field_(field),
        report_(report),
        poll_(poll),
        slope_(1.0 + field.Slope()),
        stop_gap_(0.5 * tolerance * field.r_max()) {}

  // G(x) against the points within 2 r_max; +infinity when there are none.
  double Gap(Vec2 x, double rx) const {
    double g = std::numeric_limits<double>::infinity();
    grid_.AnyNear(Grown(Rect{x.x, x.y, x.x, x.y}, 2.0 * field_.r_max()), [&](const FieldPoint& q) {
      const double d = std::sqrt(SquaredDistance(x, q.p));
      g = std::min(g, d - std::max(rx, q.r));
      return false;
    });
    if (largest_exclusion_ > 0.0) {
      exclusions_.AnyNear(Grown(Rect{x.x, x.y, x.x, x.y}, largest_exclusion_),
                          [&](const FieldPoint& c) {
                            g = std::min(g, std::sqrt(SquaredDistance(x, c.p)) - c.r);
                            return false;
                          });
    }
    return g;
  }

  void Judge(const Rect& c, double finest) {
    if (poll_.Stopped()) return;  // the caller returns CANCELLED, whatever the report says
    if (field_.HasMask() && field_.AllMasked(c)) return;
    const Vec2 centre{0.5 * (c.x0 + c.x1), 0.5 * (c.y0 + c.y1)};
    const double half_diagonal = 0.5 * std::hypot(c.Width(), c.Height());
    const double g = Gap(centre, field_.Evaluate(centre));
    const double bound = g + slope_ * half_diagonal * (1.0 + 1e-9) + 1e-12 * field_.r_max();
    if (bound < 0.0) return;
    // Once a gap beyond the tolerance is found the verdict is known; refining the cells along
    // the edge of a gap would cost one cell per 2^-32 r_min of its length.
    if (report_->largest_gap >= stop_gap_) {
      report_->gap_bound = std::max(report_->gap_bound, bound);
      return;
    }
    if (field_.HasMask() && field_.AnyMasked(c)) {
      Rect pieces[4];
      const int n = field_.CutAtPixelLines(c, pieces);
      for (int k = 0; k < n; ++k) Judge(pieces[k], finest);
      if (n > 0) return;
    } else {
      if (g > report_->largest_gap) {
        report_->largest_gap = g;
        report_->largest_gap_spot = centre;
      }
      // A gap beyond the tolerance is a verdict already; refining it would only cost time.
      if (g >= stop_gap_) {
        report_->gap_bound = std::max(report_->gap_bound, bound);
        return;
      }
    }
    if (c.Width() <= finest && c.Height() <= finest) {
      report_->gap_bound = std::max(report_->gap_bound, bound);
      return;
    }
    const double mx = 0.5 * (c.x0 + c.x1);
    const double my = 0.5 * (c.y0 + c.y1);
    Judge({c.x0, c.y0, mx, my}, finest);
    Judge({mx, c.y0, c.x1, my}, finest);
    Judge({c.x0, my, mx, c.y1}, finest);
    Judge({mx, my, c.x1, c.y1}, finest);
  }

 private:
  const FieldPointGrid& grid_;
  const FieldPointGrid& exclusions_;
  double largest_exclusion_;
  const RadiusField& field_;
  FieldVerifyReport* report_;
  StopPoll& poll_;
  double slope_;
  double stop_gap_;
};

Status Stopped() { return Cancelled("verify: stopped before the end (its caller has gone)"); }

// VerifyFieldDomain and VerifyFieldWindow: `area` is the domain, or with `window` the window
// whose pairs and spots are judged while the points outside it are context.
StatusOr<FieldVerifyReport> Verify(std::span<const Vec2> points, const Rect& area,
                                   const RadiusField& field, const FieldVerifyOptions& options,
                                   bool window) {
  const Rect& domain = area;
  if (!std::isfinite(domain.x0) || !std::isfinite(domain.y0) || !std::isfinite(domain.x1) ||
      !std::isfinite(domain.y1) || !(domain.x0 < domain.x1) || !(domain.y0 < domain.y1)) {
    return InvalidArgument(std::string(window ? "window" : "domain") +
                           " must be a finite rectangle with x0 < x1 and y0 < y1");
  }
  if (!std::isfinite(options.max_tolerance) || options.max_tolerance < 0.0) {
    return InvalidArgument("max_tolerance must be finite and >= 0");
  }
  if (!(FieldDomainCells(domain, field.r_min()) <= kMaxFieldDomainCells)) {
    return InvalidArgument(
        std::string(window ? "window" : "domain") +
        " (width / field.r_min + 2) * (height / field.r_min + 2) must be at most 6.4e7");
  }
  for (const Vec2& p : points) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) {
      return InvalidArgument("points must be finite");
    }
  }
  FieldVerifyReport report;
  const double r_max = field.r_max();
  FieldPointGrid grid(Grown(domain, 2.0 * r_max), r_max);
  std::vector<char> judged(points.size());
  for (size_t k = 0; k < points.size(); ++k) {
    const double radius = field.Evaluate(points[k]);
    judged[k] = !window || domain.Contains(points[k]);
    if (judged[k]) {
      ++report.points_checked;
      if (!domain.Contains(points[k])) ++report.points_outside;
      if (field.IsMasked(points[k])) ++report.points_masked;
    }
    grid.Add(points[k], radius);
  }
  // Pairs: the grid files points in insertion order, so a point's index is its position.
  const std::vector<FieldPoint>& filed = grid.points();
  StopPoll poll(options.stop);
  for (size_t a = 0; a < filed.size(); ++a) {
    if (poll.Stopped()) return Stopped();
    const Vec2 p = filed[a].p;
    grid.AnyNear(Grown(Rect{p.x, p.y, p.x, p.y}, r_max), [&](const FieldPoint& q) {
      const auto b = static_cast<size_t>(&q - filed.data());
      if (b <= a || !(judged[a] || judged[b])) return false;
      ++report.pairs_checked;
      const double dx = p.x - q.p.x;
      const double dy = p.y - q.p.y;
      const double m = std::max(filed[a].r, q.r);
      const double d2 = dx * dx + dy * dy;
      if (d2 < m * m) ++report.conflicts;
      const double ratio = std::sqrt(d2) / m;
      if (ratio < report.min_spacing_ratio) {
        report.min_spacing_ratio = ratio;
        report.closest_index_a = static_cast<int64_t>(a);
        report.closest_index_b = static_cast<int64_t>(b);
      }
      return false;
    });
  }
  report.conflict_ok = report.conflicts == 0;
  double largest_exclusion = 0.0;
  for (const ExclusionDisk& c : options.exclusions) {
    if (!std::isfinite(c.centre.x) || !std::isfinite(c.centre.y) || !std::isfinite(c.radius) ||
        c.radius < 0.0) {
      return InvalidArgument("exclusions must be finite disks with radius >= 0");
    }
    largest_exclusion = std::max(largest_exclusion, c.radius);
  }
  FieldPointGrid exclusions(Grown(domain, largest_exclusion), std::max(largest_exclusion, r_max));
  for (const ExclusionDisk& c : options.exclusions) exclusions.Add(c.centre, c.radius);
  if (points.empty() && options.exclusions.empty()) {
    report.largest_gap = report.gap_bound = std::numeric_limits<double>::infinity();
  } else {
    GapSearch search(grid, exclusions, largest_exclusion, field, options.max_tolerance, &report,
                     poll);
    const double base = 0.5 * r_max;
    const double finest = field.r_min() * 0x1.0p-32;
    ForEachTile(domain, base, [&](const Rect& tile) { search.Judge(tile, finest); });
    if (poll.Stopped()) return Stopped();
  }
  report.maximal_ok = report.gap_bound < options.max_tolerance * r_max;
  return report;
}

}  // namespace

StatusOr<FieldVerifyReport> VerifyFieldDomain(std::span<const Vec2> points, const Rect& domain,
                                              const RadiusField& field,
                                              const FieldVerifyOptions& options) {
  return Verify(points, domain, field, options, /*window=*/false);
}

StatusOr<FieldVerifyReport> VerifyFieldWindow(std::span<const Vec2> points, const Rect& window,
                                              const RadiusField& field,
                                              const FieldVerifyOptions& options) {
  return Verify(points, window, field, options, /*window=*/true);
}

}  // namespace scallop
