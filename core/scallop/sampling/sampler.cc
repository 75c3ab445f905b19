// Sample(): validation of SamplerOptions and dispatch to the algorithms.
#include "scallop/sampling/sampler.h"

#include <array>
#include <cmath>
#include <utility>

#include "scallop/base/precision_range.h"
#include "scallop/random/rng.h"
#include "scallop/sampling/baseline_samplers.h"
#include "scallop/sampling/boundary_sampler.h"
#include "scallop/sampling/sampling_problem.h"
#include "scallop/sampling/scalloped_sampler.h"

namespace scallop {
namespace {

constexpr std::array<std::pair<Algorithm, std::string_view>, 6> kAlgorithmNames{{
    {Algorithm::kA1, "a1"},
    {Algorithm::kA2, "a2"},
    {Algorithm::kA3, "a3"},
    {Algorithm::kDartThrowing, "dart"},
    {Algorithm::kBestCandidate, "best-candidate"},
    {Algorithm::kBridson, "bridson"},
}};

// Hexagonal packing, the densest set with spacing d, has 2 / (sqrt(3) d^2)
// points per unit area: no sampler can exceed it.
constexpr double kDensestPointsPerUnitArea = 1.1547005383792515;

}  // namespace

std::string_view AlgorithmName(Algorithm algorithm) {
  for (const auto& [a, name] : kAlgorithmNames) {
    if (a == algorithm) return name;
  }
  return "unknown";
}

StatusOr<Algorithm> ParseAlgorithm(std::string_view name) {
  for (const auto& [a, n] : kAlgorithmNames) {
    if (n == name) return a;
  }
  return InvalidArgument("algorithm: unknown '" + std::string(name) +
                         "' (expected a1, a2, a3, dart, best-candidate or bridson)");
}

bool UsesDensity(Algorithm algorithm) {
  return algorithm == Algorithm::kA1 || algorithm == Algorithm::kA2;
}

Status ValidateSamplerOptions(const SamplerOptions& options) {
  const Rect& r = options.domain.rect;
  const double d = options.min_distance;
  if (!(d >= kSmallestMinDistance && d <= kLargestMinDistance)) {
    return InvalidArgument("min_distance: must be within [2^-256, 2^256], got " +
                           std::to_string(d));
  }
  const std::pair<const char*, double> corners[] = {
      {"domain.x0", r.x0}, {"domain.y0", r.y0}, {"domain.x1", r.x1}, {"domain.y1", r.y1}};
  for (const auto& [field, value] : corners) {
    if (!std::isfinite(value)) return InvalidArgument(std::string(field) + ": must be finite");
    if (std::abs(value) > kPrecisionRangeInD * d) {
      return OutOfRange(std::string(field) + ": |value| must be at most 2^32 * min_distance = " +
                        std::to_string(kPrecisionRangeInD * d));
    }
  }
  if (!(r.x0 < r.x1)) return InvalidArgument("domain: x0 must be less than x1");
  if (!(r.y0 < r.y1)) return InvalidArgument("domain: y0 must be less than y1");
  if (options.domain.torus && (r.Width() < 8 * d || r.Height() < 8 * d)) {
    return InvalidArgument("domain: a torus needs width and height of at least 8 * min_distance");
  }
  const double most_points = r.Area() / (d * d) * kDensestPointsPerUnitArea;
  if (most_points > kMaxSamplerPoints) {
    return InvalidArgument("domain: area / min_distance^2 too large (up to " +
                           std::to_string(static_cast<int64_t>(most_points)) +
                           " points; the limit is " +
                           std::to_string(static_cast<int64_t>(kMaxSamplerPoints)) + ")");
  }
  // The samplers' grids cover the domain grown by up to 3 d a side, a cell
  // per d^2 / 2: a long thin domain passes the test above yet would need a
  // grid beyond any memory (bad_alloc, a crash), so its grown area is
  // bounded too.
  const double grown_points =
      (r.Width() + 8 * d) * (r.Height() + 8 * d) / (d * d) * kDensestPointsPerUnitArea;
  if (grown_points > kMaxSamplerPoints) {
    return InvalidArgument(
        "domain: too large for min_distance once grown by 4 * min_distance a "
        "side, as the samplers' grids are (up to " +
        std::to_string(static_cast<int64_t>(grown_points)) + " points; the limit is " +
        std::to_string(static_cast<int64_t>(kMaxSamplerPoints)) + ")");
  }
  if (UsesDensity(options.algorithm) &&
      (!std::isfinite(options.density) || options.density <= 1.0 || options.density > 2.0)) {
    return InvalidArgument("density: r'/2r must be in (1, 2], got " +
                           std::to_string(options.density));
  }
  if (options.dart_failure_limit <= 0) {
    return InvalidArgument("dart_failure_limit: must be > 0");
  }
  if (options.bridson_attempts <= 0) return InvalidArgument("bridson_attempts: must be > 0");
  if (options.best_candidate_factor <= 0) {
    return InvalidArgument("best_candidate_factor: must be > 0");
  }
  return Status::Ok();
}

StatusOr<std::vector<Vec2>> Sample(const SamplerOptions& options) {
  if (Status status = ValidateSamplerOptions(options); !status.ok()) return status;
  SamplingProblem problem;
  problem.domain = options.domain;
  problem.min_distance = options.min_distance;
  problem.density = options.density;
  // One stream per (seed, algorithm), so that algorithms never share draws.
  Rng rng(HashWords({options.seed, static_cast<uint64_t>(options.algorithm)}));
  switch (options.algorithm) {
    case Algorithm::kA1:
      // Density 2 is dart throwing, exactly; below it the paper's restriction to r' packs denser.
      return SampleScalloped(problem, CandidateChoice::kByArea, rng, A1Bulk::kCells,
                             options.density == 2.0 ? A1Reach::kAnywhere : A1Reach::kNearPoints);
    case Algorithm::kA2:
      return SampleScalloped(problem, CandidateChoice::kUniform, rng);
    case Algorithm::kA3:
      return SampleBoundary(problem, rng);
    case Algorithm::kDartThrowing:
      return options.dart_exhaustive ? SampleExhaustiveDartThrowing(problem, rng)
                                     : SampleDartThrowing(problem, options.dart_failure_limit, rng);
    case Algorithm::kBestCandidate:
      return SampleBestCandidate(problem, options.best_candidate_factor, rng);
    case Algorithm::kBridson:
      return SampleBridson(problem, options.bridson_attempts, rng);
  }
  return Status(StatusCode::kInternal, "algorithm: unhandled");
}

}  // namespace scallop
