// A3's density against the shape of its growth front (docs/quality.md, "What
// remains"): what a generator version that removes A3's seam effects has to
// work with. Bounded A3 (d = 1) three ways, each over SEEDS seeds, points per
// d^2 in 1 d bins:
//   point    a 200 d square grown from its centre, by distance to the centre;
//   flat     [0, 80) x [0, 400) grown from one straight front at x = 0, by x;
//   meeting  [0, GAP) x [0, 400) grown from two straight fronts, x = 0 and
//            x = GAP, which meet in between, by x;
//   frozen   the same, but the front at x = GAP only constrains (its points
//            are inert: they seed nothing), so one front grows into it.
// A straight front is a cut through A3's interior: the points with x in
// [-2, 0) of an A3 sample of [-12, 12) x [0, 400) (a sample's own edge would be
// a wall layer), mirrored for the right front. Points within 3 d of the
// strips' ends (y) are left out.
//
// Usage: a3_front_density [seeds=300] [gap in d=16]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <vector>

#include "scallop/random/rng.h"
#include "scallop/sampling/boundary_sampler.h"

namespace {

using scallop::Rect;
using scallop::Rng;
using scallop::SampleBoundary;
using scallop::SamplingProblem;
using scallop::Vec2;

constexpr double kStripHeight = 400;
constexpr double kEndMargin = 3;

// Points and area per 1 d bin of a profile.
struct Profile {
  std::vector<double> points;
  std::vector<double> area;
  explicit Profile(int bins) : points(bins), area(bins) {}
  void Print(const char* name) const {
    std::printf("%s", name);
    for (size_t bin = 0; bin < points.size(); ++bin) {
      if (area[bin] > 0) std::printf(" %zu:%.4f", bin, points[bin] / area[bin]);
    }
    std::printf("\n");
  }
};

// A3 on `rect` grown from the origin.
std::vector<Vec2> SampleFromOrigin(const Rect& rect, uint64_t seed) {
  SamplingProblem problem;
  problem.domain.rect = rect;
  problem.min_distance = 1.0;
  problem.seed_area = Rect{-1e-9, -1e-9, 1e-9, 1e-9};
  Rng rng(seed);
  return SampleBoundary(problem, rng);
}

// A straight front along x = 0 facing +x: see the file's comment.
std::vector<Vec2> StraightFront(uint64_t seed) {
  std::vector<Vec2> front;
  for (Vec2 p : SampleFromOrigin(Rect{-12, 0, 12, kStripHeight}, seed)) {
    if (p.x >= -2 && p.x < 0) front.push_back(p);
  }
  return front;
}

void AddGrownFromPoint(uint64_t seed, Profile& profile) {
  for (Vec2 p : SampleFromOrigin(Rect{-100, -100, 100, 100}, seed)) {
    const auto bin = static_cast<size_t>(std::hypot(p.x, p.y));
    if (bin < profile.points.size()) profile.points[bin] += 1;
  }
  for (size_t bin = 0; bin < profile.area.size(); ++bin) {
    profile.area[bin] += std::numbers::pi * static_cast<double>(2 * bin + 1);
  }
}

// The two straight fronts of one seed, both along x = 0 facing +x: the right
// one is mirrored into place by the run that uses it.
struct Fronts {
  std::vector<Vec2> left;
  std::vector<Vec2> right;
};

enum class RightSide { kNone, kGrowing, kFrozen };

// Grows [0, width) from fronts.left at x = 0, and fronts.right at x = width as `right` says.
void AddGrownFromFronts(uint64_t seed, const Fronts& fronts, double width, RightSide right,
                        Profile& profile) {
  std::vector<Vec2> fixed = fronts.left;
  std::vector<Vec2> inert;
  if (right != RightSide::kNone) {
    std::vector<Vec2>& side = right == RightSide::kGrowing ? fixed : inert;
    for (Vec2 p : fronts.right) side.push_back(Vec2{width - p.x, p.y});
  }
  SamplingProblem problem;
  problem.domain.rect = Rect{0, 0, width, kStripHeight};
  problem.min_distance = 1.0;
  problem.fixed_points = fixed;
  problem.inert_points = inert;
  Rng rng(seed);
  for (Vec2 p : SampleBoundary(problem, rng)) {
    if (p.y < kEndMargin || p.y >= kStripHeight - kEndMargin) continue;
    const auto bin = static_cast<size_t>(p.x);
    if (bin < profile.points.size()) profile.points[bin] += 1;
  }
  for (double& area : profile.area) area += kStripHeight - 2 * kEndMargin;
}

}  // namespace

int main(int argc, char** argv) {
  const int seeds = argc > 1 ? std::atoi(argv[1]) : 300;
  const int gap = argc > 2 ? std::atoi(argv[2]) : 16;
  if (seeds < 1 || gap < 2 || gap > 200) {
    std::fprintf(stderr, "usage: a3_front_density [seeds >= 1] [gap in d, 2 to 200]\n");
    return 2;
  }
  Profile point(60);
  Profile flat(80);
  Profile meeting(gap);
  Profile frozen(gap);
  for (int s = 0; s < seeds; ++s) {
    const auto seed = static_cast<uint64_t>(1000 + s);
    const Fronts fronts{StraightFront(2 * seed), StraightFront(2 * seed + 1)};
    AddGrownFromPoint(seed, point);
    AddGrownFromFronts(seed, fronts, 80, RightSide::kNone, flat);
    AddGrownFromFronts(seed, fronts, gap, RightSide::kGrowing, meeting);
    AddGrownFromFronts(seed, fronts, gap, RightSide::kFrozen, frozen);
  }
  point.Print("point");
  flat.Print("flat");
  meeting.Print("meeting");
  frozen.Print("frozen");
}
