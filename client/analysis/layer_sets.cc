#include "client/analysis/layer_sets.h"

#include <algorithm>
#include <cstdint>
#include <utility>

#include "scallop/plane/world_layers.h"
#include "scallop/random/rng.h"
#include "scallop/sampling/layered_sampler.h"
#include "scallop/sampling/multiclass_darts.h"

namespace scallop::cli {
namespace {

constexpr int64_t kWeiFailureLimit = 100000;

Status LedByDomain(const Status& status) {
  return {status.code(), "--domain: " + status.message()};
}

PlanePoints WithoutIds(LayeredPoints points) {
  PlanePoints set;
  set.positions = std::move(points.positions);
  set.layers = std::move(points.layers);
  return set;
}

// Wei's run for the layers of `options`, aiming at the counts of `ordered` by layer.
StatusOr<LayeredPoints> WeiLike(const LayeredSamplerOptions& options, const LayeredPoints& ordered,
                                uint64_t seed) {
  MultiClassDartOptions wei;
  wei.layers = options;
  wei.targets.assign(options.layers.size(), 0);
  for (uint8_t layer : ordered.layers) ++wei.targets[layer];
  // A layer the ordered run left empty still gets a dart now and then.
  for (int64_t& target : wei.targets) target = std::max<int64_t>(target, 1);
  wei.failure_limit = kWeiFailureLimit;
  wei.seed = HashWords({seed, 0x574549});  // "WEI": a stream of its own
  return SampleMultiClassDarts(wei);
}

}  // namespace

StatusOr<std::vector<PlanePoints>> WorldLayerSets(const World& world, const Rect& window, int sets,
                                                  PlaneEngine& engine) {
  std::vector<PlanePoints> result;
  for (int s = 0; s < sets; ++s) {
    StatusOr<PlanePoints> points =
        engine.Points(world.WithSeed(world.seed() + static_cast<uint64_t>(s)), window);
    if (!points.ok()) return points.status();
    result.push_back(*std::move(points));
  }
  return result;
}

StatusOr<std::vector<PlanePoints>> BoundedLayerSets(const World& world, const Rect& domain,
                                                    const std::string& algorithm, int sets) {
  if (algorithm != "a3" && algorithm != "wei") {
    return InvalidArgument(
        "--algorithm: layers on a --domain take a3 (one layer after "
        "another) or wei (Wei's multi-class darts), got " +
        algorithm);
  }
  std::vector<PlanePoints> result;
  for (int s = 0; s < sets; ++s) {
    const World reseeded = world.WithSeed(world.seed() + static_cast<uint64_t>(s));
    const LayeredSamplerOptions options = BoundedLayersOn(*reseeded.layers(), domain);
    for (size_t k = 0; k < options.layers.size() && algorithm == "wei"; ++k) {
      if (options.layers[k].field != nullptr) {
        return InvalidArgument("--algorithm: wei takes layers of constant spacing; " +
                               world.layers()->name(static_cast<int>(k)) + " has a radius field");
      }
    }
    StatusOr<LayeredPoints> ordered = SampleLayers(options);
    if (!ordered.ok()) return LedByDomain(ordered.status());
    if (algorithm == "a3") {
      result.push_back(WithoutIds(*std::move(ordered)));
      continue;
    }
    StatusOr<LayeredPoints> joint = WeiLike(options, *ordered, reseeded.seed());
    if (!joint.ok()) return LedByDomain(joint.status());
    result.push_back(WithoutIds(*std::move(joint)));
  }
  return result;
}

}  // namespace scallop::cli
