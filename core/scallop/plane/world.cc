// World validation, normalisation and fingerprint; the world algorithms' names.
#include "scallop/plane/world.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <sstream>
#include <utility>

#include "scallop/base/number_text.h"
#include "scallop/base/precision_range.h"
#include "scallop/plane/world_layers.h"
#include "scallop/random/rng.h"

namespace scallop {
namespace {

constexpr std::array<std::pair<WorldAlgorithm, std::string_view>, 3> kWorldAlgorithmNames{{
    {WorldAlgorithm::kA1, "a1"},
    {WorldAlgorithm::kA2, "a2"},
    {WorldAlgorithm::kA3, "a3"},
}};

Status ValidateSpec(const WorldSpec& spec) {
  const double d = spec.min_distance;
  if (!(d >= kSmallestMinDistance && d <= kLargestMinDistance)) {
    return InvalidArgument("world.min_distance: must be within [2^-256, 2^256], got " +
                           NumberText(d));
  }
  if (!std::any_of(kWorldAlgorithmNames.begin(), kWorldAlgorithmNames.end(),
                   [&](const auto& entry) { return entry.first == spec.algorithm; })) {
    return InvalidArgument("world.algorithm: must be a1, a2 or a3, got " +
                           std::to_string(static_cast<int>(spec.algorithm)));
  }
  if (UsesDensity(spec.algorithm) &&
      (!std::isfinite(spec.density) || spec.density <= 1.0 || spec.density > 2.0)) {
    return InvalidArgument("world.density: r'/2r must be in (1, 2] for a1 and a2, got " +
                           NumberText(spec.density));
  }
  if (spec.generator_version != kGeneratorVersion) {
    return InvalidArgument("world.generator_version: this build generates version " +
                           std::to_string(kGeneratorVersion) + ", got " +
                           std::to_string(spec.generator_version));
  }
  return Status::Ok();
}

// A field's error in the world's namespace: "field.r_min must ..." becomes
// "world.radius_field.r_min must ...", "raster.pixel_size ..." becomes
// "world.radius_field.raster.pixel_size ...".
Status InWorldNamespace(const Status& field_status) {
  std::string_view message = field_status.message();
  constexpr std::string_view kFieldPrefix = "field.";
  if (message.starts_with(kFieldPrefix)) message.remove_prefix(kFieldPrefix.size());
  return Status(field_status.code(), "world.radius_field." + std::string(message));
}

uint64_t Fingerprint(const WorldSpec& spec, const RadiusField* field) {
  if (field == nullptr) {
    return HashWords({spec.seed, std::bit_cast<uint64_t>(spec.min_distance),
                      static_cast<uint64_t>(spec.algorithm), std::bit_cast<uint64_t>(spec.density),
                      spec.generator_version});
  }
  return HashWords({spec.seed, std::bit_cast<uint64_t>(spec.min_distance),
                    static_cast<uint64_t>(spec.algorithm), std::bit_cast<uint64_t>(spec.density),
                    spec.generator_version, field->Fingerprint()});
}

}  // namespace

std::string_view WorldAlgorithmName(WorldAlgorithm algorithm) {
  for (const auto& [a, name] : kWorldAlgorithmNames) {
    if (a == algorithm) return name;
  }
  return "unknown";
}

StatusOr<WorldAlgorithm> ParseWorldAlgorithm(std::string_view name, std::string_view field) {
  for (const auto& [a, n] : kWorldAlgorithmNames) {
    if (n == name) return a;
  }
  return InvalidArgument(std::string(field) + ": must be a1, a2 or a3, got '" + std::string(name) +
                         "'");
}

bool UsesDensity(WorldAlgorithm algorithm) {
  return algorithm == WorldAlgorithm::kA1 || algorithm == WorldAlgorithm::kA2;
}

Algorithm SamplerAlgorithm(WorldAlgorithm algorithm) {
  switch (algorithm) {
    case WorldAlgorithm::kA1:
      return Algorithm::kA1;
    case WorldAlgorithm::kA2:
      return Algorithm::kA2;
    case WorldAlgorithm::kA3:
      break;
  }
  return Algorithm::kA3;
}

World::World(const WorldSpec& spec, std::shared_ptr<const RadiusField> field)
    : spec_(spec), field_(std::move(field)), fingerprint_(Fingerprint(spec_, field_.get())) {}

StatusOr<World> World::Create(const WorldSpec& spec) {
  if (!spec.layers.empty() || !spec.exclusions.empty()) return WorldLayers::Create(spec);
  return CreatePlain(spec);
}

StatusOr<World> World::CreatePlain(const WorldSpec& spec) {
  WorldSpec canonical = spec;
  std::shared_ptr<const RadiusField> field;
  if (spec.radius_field.has_value()) {
    StatusOr<RadiusField> made = RadiusField::Create(*spec.radius_field);
    if (!made.ok()) return InWorldNamespace(made.status());
    // The field's own r_min is in the range d may take, so the checks below
    // see a valid d.
    canonical.min_distance = made->r_min();
    if (made->kind() == RadiusFieldKind::kConstant) {
      canonical.radius_field.reset();
    } else {
      if (spec.algorithm != WorldAlgorithm::kA3) {
        return InvalidArgument(
            "world.algorithm: a world with a radius field must use a3 (only A3's growth takes "
            "a field), got " +
            std::string(WorldAlgorithmName(spec.algorithm)));
      }
      field = std::make_shared<const RadiusField>(*std::move(made));
      canonical.radius_field = field->spec();
    }
  }
  if (Status status = ValidateSpec(canonical); !status.ok()) return status;
  if (!UsesDensity(canonical.algorithm)) canonical.density = 2.0;
  return World(canonical, std::move(field));
}

World World::WithSeed(uint64_t seed) const {
  WorldSpec spec = spec_;
  spec.seed = seed;
  // A valid layered spec stays valid with any seed.
  if (layers_ != nullptr) return *WorldLayers::Create(spec);
  return World(spec, field_);
}

bool operator==(const World& a, const World& b) {
  if ((a.layers_ == nullptr) != (b.layers_ == nullptr) ||
      (a.earlier_ == nullptr) != (b.earlier_ == nullptr)) {
    return false;
  }
  if (a.layers_ != nullptr || a.earlier_ != nullptr) return a.fingerprint_ == b.fingerprint_;
  const WorldSpec& x = a.spec_;
  const WorldSpec& y = b.spec_;
  if (x.seed != y.seed || x.min_distance != y.min_distance || x.algorithm != y.algorithm ||
      x.density != y.density || x.generator_version != y.generator_version) {
    return false;
  }
  if ((a.field_ == nullptr) != (b.field_ == nullptr)) return false;
  return a.field_ == nullptr || a.field_->Fingerprint() == b.field_->Fingerprint();
}

std::string World::Describe() const {
  std::ostringstream out;
  if (layers_ != nullptr) {
    out << "seed=" << seed() << " algorithm=" << WorldAlgorithmName(algorithm());
    if (UsesDensity(algorithm())) out << " density=" << NumberText(density());
    out << " version=" << generator_version() << " layers=[";
    for (int k = 0; k < layers_->count(); ++k) {
      // Each layer's spacing as the canonical spec gives it.
      const LayerSpec& layer = spec_.layers[static_cast<size_t>(k)];
      out << (k > 0 ? " " : "") << layer.name << ":";
      if (!layer.radius_field.has_value()) {
        out << "d=" << NumberText(layer.min_distance);
      } else {
        out << "field=" << RadiusFieldKindName(layer.radius_field->kind) << " r=["
            << NumberText(layer.radius_field->r_min) << "," << NumberText(layer.radius_field->r_max)
            << "]";
      }
    }
    out << "] exclusions=[";
    bool first = true;
    for (int a = 0; a < layers_->count(); ++a) {
      for (int b = a + 1; b < layers_->count(); ++b) {
        out << (first ? "" : " ") << layers_->name(a) << "," << layers_->name(b) << "="
            << NumberText(layers_->exclusion(a, b));
        first = false;
      }
    }
    out << "] layers_hash=" << std::hex << fingerprint_ << std::dec;
    return out.str();
  }
  out << "seed=" << seed() << " d=" << NumberText(min_distance())
      << " algorithm=" << WorldAlgorithmName(algorithm());
  if (UsesDensity(algorithm())) out << " density=" << NumberText(density());
  out << " version=" << generator_version();
  if (field_ != nullptr) {
    const RadiusFieldSpec& f = field_->spec();
    out << " field=" << RadiusFieldKindName(f.kind) << " r=[" << NumberText(f.r_min) << ","
        << NumberText(f.r_max) << "]";
    if (f.kind == RadiusFieldKind::kNoise) {
      out << " frequency=" << NumberText(f.frequency) << " octaves=" << f.octaves
          << " gain=" << NumberText(f.gain) << " noise_seed=" << f.noise_seed;
    } else if (f.kind == RadiusFieldKind::kRaster) {
      out << " raster=" << f.raster->width << "x" << f.raster->height << "x" << f.raster->bit_depth
          << " origin=(" << NumberText(f.raster_origin.x) << "," << NumberText(f.raster_origin.y)
          << ") pixel_size=" << NumberText(f.pixel_size) << " field_hash=" << std::hex
          << field_->Fingerprint() << std::dec;
    }
  }
  return out.str();
}

}  // namespace scallop
