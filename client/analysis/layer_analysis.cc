// AnalyseLayers: per-layer and union periodograms and rho, and cross-layer pair-distance
// histograms through a grid of the other layer's points.
#include "client/analysis/layer_analysis.h"

#include <algorithm>
#include <cmath>

#include "scallop/analysis/point_statistics.h"
#include "scallop/plane/world_layers.h"
#include "scallop/sampling/field_point_grid.h"

namespace scallop::cli {
namespace {

constexpr double kCrossRatioLimit = 3.0;

// The spectrum of the points of `set` whose layer `wanted` accepts (every point for -1).
Status AddSet(const PlanePoints& set, int wanted, const Rect& window, int max_frequency,
              PeriodogramAverage& average, LayerSpectrum& spectrum) {
  std::vector<Vec2> points;
  for (size_t k = 0; k < set.positions.size(); ++k) {
    if (wanted < 0 || set.layers[k] == wanted) points.push_back(set.positions[k]);
  }
  if (points.empty()) {
    return InvalidArgument("--rect: a set has no point of " + spectrum.name +
                           "; give a larger window");
  }
  StatusOr<Periodogram> periodogram = ComputePeriodogram(points, window, max_frequency);
  if (!periodogram.ok()) return periodogram.status();
  if (Status status = average.Add(*periodogram); !status.ok()) return status;
  StatusOr<double> rho = NormalisedRadius(static_cast<int64_t>(points.size()),
                                          window.Width() * window.Height(), spectrum.spacing);
  if (!rho.ok()) return rho.status();
  spectrum.rho += *rho;
  spectrum.points += static_cast<int64_t>(points.size());
  return Status::Ok();
}

}  // namespace

StatusOr<LayeredAnalysis> AnalyseLayers(const std::vector<PlanePoints>& sets, const World& world,
                                        const Rect& window, int max_frequency) {
  const WorldLayers& layers = *world.layers();
  const int n = layers.count();
  LayeredAnalysis analysis;
  // Each layer, then the union (wanted = -1).
  for (int wanted = 0; wanted <= n; ++wanted) {
    const bool is_union = wanted == n;
    LayerSpectrum spectrum;
    spectrum.name = is_union ? "union" : layers.name(wanted);
    spectrum.spacing = is_union ? world.min_distance() : layers.world(wanted).min_distance();
    PeriodogramAverage average;
    for (const PlanePoints& set : sets) {
      if (Status status =
              AddSet(set, is_union ? -1 : wanted, window, max_frequency, average, spectrum);
          !status.ok()) {
        return status;
      }
    }
    spectrum.rho /= static_cast<double>(sets.size());
    StatusOr<Periodogram> mean = average.Mean();
    if (!mean.ok()) return mean.status();
    spectrum.periodogram = *std::move(mean);
    StatusOr<RadialSpectrum> radial = ComputeRadialSpectrum(spectrum.periodogram);
    if (!radial.ok()) return radial.status();
    spectrum.radial = *std::move(radial);
    analysis.layers.push_back(std::move(spectrum));
  }

  const auto bins = static_cast<size_t>(std::lround(kCrossRatioLimit / kCrossRatioStep));
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      if (a == b) continue;
      CrossHistogram histogram{a, b, layers.exclusion(a, b), 0, std::vector<double>(bins, 0.0)};
      const double reach = kCrossRatioLimit * histogram.distance;
      if (!(histogram.distance > 0.0)) {
        analysis.cross.push_back(std::move(histogram));
        continue;
      }
      const Rect centres = Grown(window, -reach);
      for (const PlanePoints& set : sets) {
        FieldPointGrid others(window, reach);
        for (size_t k = 0; k < set.positions.size(); ++k) {
          if (set.layers[k] == b) others.Add(set.positions[k], 0.0);
        }
        for (size_t k = 0; k < set.positions.size(); ++k) {
          const Vec2 p = set.positions[k];
          if (set.layers[k] != a || !(centres.x0 < centres.x1 && centres.y0 < centres.y1) ||
              !centres.Contains(p)) {
            continue;
          }
          ++histogram.centres;
          others.AnyNear(Grown(Rect{p.x, p.y, p.x, p.y}, reach), [&](const FieldPoint& q) {
            const double ratio = std::sqrt(SquaredDistance(p, q.p)) / histogram.distance;
            const auto bin = static_cast<size_t>(ratio / kCrossRatioStep);
            if (bin < bins) histogram.per_point[bin] += 1.0;
            return false;
          });
        }
      }
      if (histogram.centres > 0) {
        for (double& count : histogram.per_point) count /= static_cast<double>(histogram.centres);
      }
      analysis.cross.push_back(std::move(histogram));
    }
  }
  return analysis;
}

}  // namespace scallop::cli
