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

World::World(const WorldSpec& spec)
    : spec_(spec),
      fingerprint_(HashWords({spec.seed, std::bit_cast<uint64_t>(spec.min_distance),
                              static_cast<uint64_t>(spec.algorithm),
                              std::bit_cast<uint64_t>(spec.density), spec.generator_version})) {}

StatusOr<World> World::Create(const WorldSpec& spec) {
  if (Status status = ValidateSpec(spec); !status.ok()) return status;
  WorldSpec canonical = spec;
  if (!UsesDensity(canonical.algorithm)) canonical.density = 2.0;
  return World(canonical);
}

World World::WithSeed(uint64_t seed) const {
  WorldSpec spec = spec_;
  spec.seed = seed;
  return World(spec);
}

std::string World::Describe() const {
  std::ostringstream out;
  out << "seed=" << seed() << " d=" << NumberText(min_distance())
      << " algorithm=" << WorldAlgorithmName(algorithm());
  if (UsesDensity(algorithm())) out << " density=" << NumberText(density());
  out << " version=" << generator_version();
  return out.str();
}

}  // namespace scallop
