// WorldLayers::Create: checks a layered spec, orders the layers, fills the exclusion matrix and
// builds each layer's world with its seed and what it keeps clear of.
#include "scallop/plane/world_layers.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <memory>

#include "scallop/base/number_text.h"
#include "scallop/random/rng.h"

namespace scallop {
namespace {

// Hashed into a layered world's fingerprint and a later layer's, so that neither can equal a
// plain world's.
constexpr uint64_t kLayeredWorldTag = 0x4c4159455245440aULL;

std::string LayerField(size_t k) { return "world.layers[" + std::to_string(k) + "]"; }
std::string ExclusionField(size_t n) { return "world.exclusions[" + std::to_string(n) + "]"; }

Status CheckName(const std::string& name, size_t k) {
  const auto allowed = [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '.' || c == '-';
  };
  if (name.empty() || name.size() > kMaxLayerNameLength ||
      !std::all_of(name.begin(), name.end(), allowed)) {
    return InvalidArgument(LayerField(k) +
                           ".name: must be 1 to 64 characters of A-Z a-z 0-9 _ . -, got '" +
                           name.substr(0, kMaxLayerNameLength + 1) + "'");
  }
  return Status::Ok();
}

// A plain world's error about its spacing in the layer's namespace: "world.min_distance: ..."
// becomes "world.layers[k].min_distance: ...", "world.radius_field.r_min ..." becomes
// "world.layers[k].radius_field.r_min ...". Errors of the world's own fields stay as they are.
Status InLayerNamespace(const Status& status, size_t k) {
  std::string_view message = status.message();
  for (std::string_view own : {"world.min_distance", "world.radius_field"}) {
    if (message.starts_with(own)) {
      message.remove_prefix(std::string_view("world").size());
      return Status(status.code(), LayerField(k) + std::string(message));
    }
  }
  return status;
}

uint64_t NameHash(const std::string& name) {
  uint64_t h = HashWords({name.size()});
  for (size_t at = 0; at < name.size(); at += 8) {
    uint64_t word = 0;
    for (size_t b = at; b < std::min(name.size(), at + 8); ++b) {
      word |= static_cast<uint64_t>(static_cast<unsigned char>(name[b])) << (8 * (b - at));
    }
    h = HashWords({h, word});
  }
  return h;
}

}  // namespace

double DefaultExclusion(const std::vector<double>& spacings, int later) {
  double density = 0.0;
  for (int c = 0; c <= later; ++c) {
    const double r = spacings[static_cast<size_t>(c)];
    density += 1.0 / (r * r);
  }
  return 1.0 / std::sqrt(density);
}

int WorldLayers::LayerNamed(std::string_view name) const {
  for (size_t k = 0; k < names_.size(); ++k) {
    if (names_[k] == name) return static_cast<int>(k);
  }
  return -1;
}

StatusOr<World> WorldLayers::Create(const WorldSpec& spec) {
  const size_t n = spec.layers.size();
  if (n == 0) {
    return InvalidArgument("world.layers: exclusions were given but no layers");
  }
  if (n > static_cast<size_t>(kMaxLayers)) {
    return InvalidArgument("world.layers: at most " + std::to_string(kMaxLayers) + " layers, got " +
                           std::to_string(n));
  }
  if (spec.radius_field.has_value()) {
    return InvalidArgument(
        "world.radius_field: a layered world gives each layer its spacing "
        "(world.layers[k].min_distance or world.layers[k].radius_field)");
  }
  if (n > 1 && spec.algorithm != WorldAlgorithm::kA3) {
    return InvalidArgument(
        "world.algorithm: a world of several layers must use a3 (its later layers grow by A3's "
        "rule around the earlier ones), got " +
        std::string(WorldAlgorithmName(spec.algorithm)));
  }

  auto layers = std::make_shared<WorldLayers>();
  std::vector<World> plain;  // each layer as a plain world with the world's seed, declared order
  for (size_t k = 0; k < n; ++k) {
    const LayerSpec& layer = spec.layers[k];
    if (Status status = CheckName(layer.name, k); !status.ok()) return status;
    for (size_t e = 0; e < k; ++e) {
      if (spec.layers[e].name == layer.name) {
        return InvalidArgument(LayerField(k) + ".name: '" + layer.name +
                               "' is already the name of " + LayerField(e));
      }
    }
    WorldSpec own{.seed = spec.seed,
                  .min_distance = layer.min_distance,
                  .algorithm = spec.algorithm,
                  .density = spec.density,
                  .generator_version = spec.generator_version,
                  .radius_field = layer.radius_field};
    StatusOr<World> made = World::CreatePlain(own);
    if (!made.ok()) return InLayerNamespace(made.status(), k);
    layers->names_.push_back(layer.name);
    plain.push_back(*std::move(made));
  }

  // Generation order: decreasing largest spacing, ties in the spec's order.
  std::vector<int>& order = layers->order_;
  for (size_t k = 0; k < n; ++k) order.push_back(static_cast<int>(k));
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return plain[static_cast<size_t>(a)].max_spacing() >
           plain[static_cast<size_t>(b)].max_spacing();
  });
  std::vector<int> position(n);  // generation position of each layer
  std::vector<double> spacings;  // largest spacing, in generation order
  for (size_t g = 0; g < n; ++g) {
    position[static_cast<size_t>(order[g])] = static_cast<int>(g);
    spacings.push_back(plain[static_cast<size_t>(order[g])].max_spacing());
  }

  // The matrix: the diagonal is each layer's own spacing; given pairs, then the default.
  layers->matrix_.assign(n * n, -1.0);
  layers->given_.assign(n * n, false);
  std::vector<size_t> given_by(n * n, 0);
  for (size_t e = 0; e < spec.exclusions.size(); ++e) {
    const LayerExclusionSpec& x = spec.exclusions[e];
    const int a = layers->LayerNamed(x.first);
    if (a < 0)
      return InvalidArgument(ExclusionField(e) + ".first: no layer named '" + x.first + "'");
    const int b = layers->LayerNamed(x.second);
    if (b < 0) {
      return InvalidArgument(ExclusionField(e) + ".second: no layer named '" + x.second + "'");
    }
    if (a == b) {
      return InvalidArgument(ExclusionField(e) + ": pairs layer '" + x.first +
                             "' with itself; a layer's own spacing is its min_distance or "
                             "radius_field");
    }
    const double bound =
        kMaxExclusionInRMax * std::max(plain[static_cast<size_t>(a)].max_spacing(),
                                       plain[static_cast<size_t>(b)].max_spacing());
    if (!std::isfinite(x.distance) || x.distance < 0.0 || x.distance > bound) {
      return InvalidArgument(ExclusionField(e) + ".distance: must be in [0, " + NumberText(bound) +
                             "] (4 times the larger spacing of '" + x.first + "' and '" + x.second +
                             "'), got " + NumberText(x.distance));
    }
    const size_t ab = static_cast<size_t>(a) * n + static_cast<size_t>(b);
    const size_t ba = static_cast<size_t>(b) * n + static_cast<size_t>(a);
    if (layers->given_[ab] && layers->matrix_[ab] != x.distance) {
      const std::string before = ExclusionField(given_by[ab]);
      const bool reversed = spec.exclusions[given_by[ab]].first != x.first;
      return InvalidArgument(ExclusionField(e) + ": " +
                             (reversed ? "the matrix is not symmetric: "
                                       : "the pair is given twice with different distances: ") +
                             x.first + "," + x.second + " = " + NumberText(x.distance) + " but " +
                             before + " gives " + NumberText(layers->matrix_[ab]));
    }
    layers->matrix_[ab] = layers->matrix_[ba] = x.distance;
    layers->given_[ab] = layers->given_[ba] = true;
    given_by[ab] = given_by[ba] = e;
  }
  for (size_t a = 0; a < n; ++a) {
    for (size_t b = 0; b < n; ++b) {
      double& d = layers->matrix_[a * n + b];
      if (a == b) {
        d = plain[a].max_spacing();
      } else if (!layers->given_[a * n + b]) {
        d = DefaultExclusion(spacings, std::max(position[a], position[b]));
      }
      if (a != b) layers->largest_exclusion_ = std::max(layers->largest_exclusion_, d);
    }
    layers->largest_spacing_ = std::max(layers->largest_spacing_, plain[a].max_spacing());
  }

  // The layers' worlds. The first generated is the plain world; each later one has its own
  // seed and keeps clear of the earlier ones, and its fingerprint hashes theirs and the
  // distances. A constant later layer is an A3 world (16 d regions; A3 cuts the disks from its
  // circles), a field layer a field world (the field sampler masks the disks).
  layers->worlds_.resize(n);
  std::vector<World> generated;
  for (size_t g = 0; g < n; ++g) {
    const auto k = static_cast<size_t>(order[g]);
    if (g == 0) {
      layers->worlds_[k] = plain[k];
      generated.push_back(plain[k]);
      continue;
    }
    WorldSpec own = plain[k].spec();
    own.seed = HashWords({spec.seed, kLayerSeedStream, static_cast<uint64_t>(g)});
    World world(own, plain[k].field_);
    auto earlier = std::make_shared<EarlierLayers>();
    uint64_t h = HashWords({world.fingerprint_, kLayeredWorldTag});
    for (size_t j = 0; j < g; ++j) {
      const double d = layers->exclusion(order[j], static_cast<int>(k));
      earlier->worlds.push_back(generated[j]);
      earlier->distances.push_back(d);
      earlier->largest_distance = std::max(earlier->largest_distance, d);
      h = HashWords({h, generated[j].fingerprint(), std::bit_cast<uint64_t>(d)});
    }
    world.earlier_ = std::move(earlier);
    world.fingerprint_ = h;
    layers->worlds_[k] = world;
    generated.push_back(world);
  }

  // The layered world itself: the rectangle rule reads its smallest spacing.
  WorldSpec canonical = spec;
  canonical.min_distance = plain.front().min_distance();
  for (size_t k = 0; k < n; ++k) {
    canonical.min_distance = std::min(canonical.min_distance, plain[k].min_distance());
    canonical.layers[k].min_distance = plain[k].min_distance();
    canonical.layers[k].radius_field = plain[k].spec().radius_field;
  }
  if (!UsesDensity(canonical.algorithm)) canonical.density = 2.0;
  World world(canonical, nullptr);
  uint64_t h = HashWords({world.fingerprint_, kLayeredWorldTag, n});
  for (size_t k = 0; k < n; ++k) {
    h = HashWords({h, NameHash(layers->names_[k]), layers->worlds_[k].fingerprint()});
  }
  for (const double d : layers->matrix_) h = HashWords({h, std::bit_cast<uint64_t>(d)});
  world.fingerprint_ = h;
  world.layers_ = std::move(layers);
  return world;
}

LayeredSamplerOptions BoundedLayersOn(const WorldLayers& layers, const Rect& domain) {
  LayeredSamplerOptions options;
  options.domain = domain;
  options.order = layers.generation_order();
  const int n = layers.count();
  for (int k = 0; k < n; ++k) {
    const World& world = layers.world(k);
    options.layers.push_back({.min_distance = world.min_distance(),
                              .field = world.radius_field(),
                              .seed = world.seed()});
    for (int b = 0; b < n; ++b) options.exclusions.push_back(k == b ? 0.0 : layers.exclusion(k, b));
  }
  return options;
}

}  // namespace scallop
