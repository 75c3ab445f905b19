#include "scallop/sampling/layered_sampler.h"

#include <cmath>
#include <string>

#include "scallop/plane/layer_spec.h"
#include "scallop/random/rng.h"
#include "scallop/sampling/boundary_sampler.h"
#include "scallop/sampling/field_sampler.h"
#include "scallop/sampling/sampler.h"
#include "scallop/sampling/sampling_problem.h"

namespace scallop {
namespace {

// Sample's options for a constant layer: the stream Sample gives A3, so that a layer sampled
// first is Sample's run.
SamplerOptions ConstantLayerOptions(const Rect& domain, const BoundedLayer& layer) {
  return {.algorithm = Algorithm::kA3,
          .domain = {domain, false},
          .min_distance = layer.min_distance,
          .seed = layer.seed};
}

double LargestSpacing(const BoundedLayer& layer) {
  return layer.field != nullptr ? layer.field->r_max() : layer.min_distance;
}

Status LedByLayer(size_t k, const Status& status) {
  return {status.code(), "layers[" + std::to_string(k) + "]: " + status.message()};
}

Status ValidateOrder(const LayeredSamplerOptions& options) {
  const size_t n = options.layers.size();
  if (options.order.size() != n) {
    return InvalidArgument("order: must name each of the " + std::to_string(n) +
                           " layers once, got " + std::to_string(options.order.size()));
  }
  std::vector<bool> seen(n, false);
  for (size_t g = 0; g < n; ++g) {
    const int k = options.order[g];
    if (k < 0 || static_cast<size_t>(k) >= n || seen[static_cast<size_t>(k)]) {
      return InvalidArgument("order[" + std::to_string(g) + "]: must be a layer number below " +
                             std::to_string(n) + " not named before, got " + std::to_string(k));
    }
    seen[static_cast<size_t>(k)] = true;
  }
  return Status::Ok();
}

Status ValidateExclusions(const LayeredSamplerOptions& options) {
  const size_t n = options.layers.size();
  if (options.exclusions.size() != n * n) {
    return InvalidArgument("exclusions: must hold layers^2 = " + std::to_string(n * n) +
                           " entries, got " + std::to_string(options.exclusions.size()));
  }
  for (size_t a = 0; a < n; ++a) {
    for (size_t b = 0; b < n; ++b) {
      const double distance = options.exclusions[a * n + b];
      const std::string name = "exclusions[" + std::to_string(a * n + b) + "]";
      if (a == b) continue;
      if (!std::isfinite(distance) || distance < 0) {
        return InvalidArgument(name + ": must be finite and >= 0, got " + std::to_string(distance));
      }
      if (distance != options.exclusions[b * n + a]) {
        return InvalidArgument(name + ": the matrix must be symmetric");
      }
      // As a world's matrix is bounded (kMaxExclusionInRMax): a disk far wider than the
      // spacings would only cost, and its arcs' arithmetic must stay finite.
      const double bound = kMaxExclusionInRMax * std::max(LargestSpacing(options.layers[a]),
                                                          LargestSpacing(options.layers[b]));
      if (distance > bound) {
        return InvalidArgument(name + ": at most 4 times the larger spacing of its two layers (" +
                               std::to_string(bound) + "), got " + std::to_string(distance));
      }
    }
  }
  return Status::Ok();
}

}  // namespace

Status ValidateLayeredSamplerOptions(const LayeredSamplerOptions& options) {
  const size_t n = options.layers.size();
  if (n == 0 || n > 255) {
    return InvalidArgument("layers: must hold 1 to 255 layers, got " + std::to_string(n));
  }
  for (size_t k = 0; k < n; ++k) {
    const BoundedLayer& layer = options.layers[k];
    const Status status = layer.field != nullptr
                              ? ValidateFieldSamplerOptions(
                                    {.domain = options.domain, .seed = layer.seed}, *layer.field)
                              : ValidateSamplerOptions(ConstantLayerOptions(options.domain, layer));
    if (!status.ok()) return LedByLayer(k, status);
  }
  if (Status status = ValidateOrder(options); !status.ok()) return status;
  return ValidateExclusions(options);
}

StatusOr<LayeredPoints> SampleLayers(const LayeredSamplerOptions& options) {
  if (Status status = ValidateLayeredSamplerOptions(options); !status.ok()) return status;
  const size_t n = options.layers.size();
  LayeredPoints sampled;
  std::vector<ExclusionDisk> disks;
  for (const int k : options.order) {
    const BoundedLayer& layer = options.layers[static_cast<size_t>(k)];
    // The earlier layers' points, each a disk of the distance this layer keeps from its layer.
    disks.clear();
    for (size_t m = 0; m < sampled.positions.size(); ++m) {
      const double radius = options.exclusions[sampled.layers[m] * n + static_cast<size_t>(k)];
      if (radius > 0) disks.push_back({sampled.positions[m], radius});
    }
    SamplingProblem problem;
    problem.domain = {options.domain, false};
    problem.exclusions = disks;
    std::vector<Vec2> placed;
    if (layer.field != nullptr) {
      // SampleField's stream for the seed.
      Rng rng(HashWords({layer.seed, 0x4649454c44ULL}));
      placed = SampleFieldProblem(problem, *layer.field, rng, nullptr);
    } else {
      problem.min_distance = layer.min_distance;
      Rng rng(HashWords({layer.seed, static_cast<uint64_t>(Algorithm::kA3)}));
      placed = SampleBoundary(problem, rng);
    }
    sampled.positions.insert(sampled.positions.end(), placed.begin(), placed.end());
    sampled.layers.insert(sampled.layers.end(), placed.size(), static_cast<uint8_t>(k));
  }
  return sampled;
}

}  // namespace scallop
