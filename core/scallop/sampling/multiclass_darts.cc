#include "scallop/sampling/multiclass_darts.h"

#include <string>

#include "scallop/random/rng.h"
#include "scallop/sampling/point_grid.h"

namespace scallop {
namespace {

// The classes' points, a grid each (a class's own spacing apart, so one point a cell), with
// removal, and how far each class is toward its target.
class ClassSets {
 public:
  explicit ClassSets(const MultiClassDartOptions& options)
      : options_(options), counts_(options.targets.size(), 0) {
    for (const BoundedLayer& layer : options.layers.layers) {
      grids_.emplace_back(options.layers.domain, false, layer.min_distance);
    }
  }

  size_t classes() const { return counts_.size(); }
  double spacing(size_t c) const { return options_.layers.layers[c].min_distance; }
  double rule(size_t a, size_t b) const {
    return a == b ? spacing(a) : options_.layers.exclusions[a * classes() + b];
  }

  // counts[a] / targets[a] < counts[b] / targets[b], exactly.
  bool LessFilled(size_t a, size_t b) const {
    return counts_[a] * options_.targets[b] < counts_[b] * options_.targets[a];
  }
  bool AllFilled() const {
    for (size_t c = 0; c < classes(); ++c) {
      if (counts_[c] < options_.targets[c]) return false;
    }
    return true;
  }
  size_t LeastFilled() const {
    size_t least = 0;
    for (size_t c = 1; c < classes(); ++c) {
      if (LessFilled(c, least)) least = c;
    }
    return least;
  }

  // Collects into `conflicts` the points a dart of class c at p is too close to; false as soon
  // as one of them may not be pushed out (Wei: only a point of a smaller spacing whose class is
  // at least as filled as c).
  bool OnlyRemovableConflicts(size_t c, Vec2 p, std::vector<int32_t>& conflicts) const {
    conflicts.clear();
    for (size_t j = 0; j < classes(); ++j) {
      const double distance = rule(c, j);
      if (!(distance > 0.0)) continue;
      const bool removable = options_.removal && spacing(j) < spacing(c) && !LessFilled(j, c);
      bool blocked = false;
      grids_[j].ForEachNear(p, distance, [&](int32_t index, Vec2 q) {
        if (blocked || SquaredDistance(p, q) >= distance * distance) return;
        if (removable) {
          conflicts.push_back(index);
        } else {
          blocked = true;
        }
      });
      if (blocked) return false;
    }
    return true;
  }

  void Add(size_t c, Vec2 p) {
    const auto index = static_cast<int32_t>(positions_.size());
    grids_[c].Insert(index, p);
    positions_.push_back(p);
    layers_.push_back(static_cast<uint8_t>(c));
    alive_.push_back(true);
    ++counts_[c];
  }

  void Remove(int32_t index) {
    const auto k = static_cast<size_t>(index);
    grids_[layers_[k]].Remove(positions_[k]);
    alive_[k] = false;
    --counts_[layers_[k]];
  }

  // The points kept, by class, each class's in the order added.
  LayeredPoints Kept() const {
    LayeredPoints kept;
    for (size_t c = 0; c < classes(); ++c) {
      for (size_t k = 0; k < positions_.size(); ++k) {
        if (alive_[k] && layers_[k] == c) {
          kept.positions.push_back(positions_[k]);
          kept.layers.push_back(static_cast<uint8_t>(c));
        }
      }
    }
    return kept;
  }

 private:
  const MultiClassDartOptions& options_;
  std::vector<int64_t> counts_;
  std::vector<PointGrid> grids_;
  std::vector<Vec2> positions_;
  std::vector<uint8_t> layers_;
  std::vector<bool> alive_;
};

}  // namespace

Status ValidateMultiClassDartOptions(const MultiClassDartOptions& options) {
  if (Status status = ValidateLayeredSamplerOptions(options.layers); !status.ok()) return status;
  const size_t n = options.layers.layers.size();
  for (size_t k = 0; k < n; ++k) {
    if (options.layers.layers[k].field != nullptr) {
      return InvalidArgument("layers.layers[" + std::to_string(k) +
                             "].field: multi-class darts take constant spacings only");
    }
  }
  if (options.targets.size() != n) {
    return InvalidArgument("targets: must give one count per layer (" + std::to_string(n) +
                           "), got " + std::to_string(options.targets.size()));
  }
  for (size_t k = 0; k < n; ++k) {
    // Bounded so that the fill comparisons' products stay within 64 bits.
    if (options.targets[k] <= 0 || options.targets[k] > kMaxMultiClassTarget) {
      return InvalidArgument("targets[" + std::to_string(k) + "]: must be in 1.." +
                             std::to_string(kMaxMultiClassTarget) + ", got " +
                             std::to_string(options.targets[k]));
    }
  }
  if (options.failure_limit <= 0) return InvalidArgument("failure_limit: must be > 0");
  if (options.max_darts <= 0) return InvalidArgument("max_darts: must be > 0");
  return Status::Ok();
}

StatusOr<LayeredPoints> SampleMultiClassDarts(const MultiClassDartOptions& options) {
  if (Status status = ValidateMultiClassDartOptions(options); !status.ok()) return status;
  const Rect& domain = options.layers.domain;
  ClassSets sets(options);
  Rng rng(options.seed);
  std::vector<int32_t> conflicts;
  int64_t failures = 0;
  for (int64_t dart = 0; dart < options.max_darts && failures < options.failure_limit; ++dart) {
    if (sets.AllFilled()) break;
    const size_t c = sets.LeastFilled();
    const double x = rng.Uniform(domain.x0, domain.x1);
    const Vec2 p{x, rng.Uniform(domain.y0, domain.y1)};
    // Rounding may put lo + (hi - lo) u on hi, outside the half-open domain.
    if (!domain.Contains(p) || !sets.OnlyRemovableConflicts(c, p, conflicts)) {
      ++failures;
      continue;
    }
    failures = 0;
    for (int32_t index : conflicts) sets.Remove(index);
    sets.Add(c, p);
  }
  return sets.Kept();
}

}  // namespace scallop
