// `scallop analyze` for layered worlds (issue 19): each layer's spectrum and rho, the union's,
// and how each layer's points sit around another's (pair distances over D[a][b]), averaged over
// sets. What Wei (SIGGRAPH 2010) judges multi-class sampling by: each class and the union.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scallop/analysis/periodogram.h"
#include "scallop/analysis/radial_spectrum.h"
#include "scallop/base/status.h"
#include "scallop/geometry/rect.h"
#include "scallop/plane/plane_engine.h"
#include "scallop/plane/world.h"

namespace scallop::cli {

// One layer's points (or the union's) over the sets.
struct LayerSpectrum {
  std::string name;    // the layer's, or "union"
  double spacing = 0;  // its d (a field layer's r_min; the union's: the smallest)
  int64_t points = 0;  // over all sets
  // Lagae and Dutre's normalised radius over the whole window with the layer's d, mean over
  // sets: a later layer is lower, as the earlier layers' exclusions take part of the window.
  double rho = 0;
  Periodogram periodogram;  // mean over the sets
  RadialSpectrum radial;
};

// How layer b's points sit around layer a's: for the points of a at least 3 D[a][b] inside the
// window, the points of b per point of a by |p - q| / D[a][b], in bins of kCrossRatioStep from
// 0 to 3 (zero below 1 when the layers keep D).
struct CrossHistogram {
  int a = 0, b = 0;
  double distance = 0;  // D[a][b]
  int64_t centres = 0;  // points of a counted, over the sets
  std::vector<double> per_point;
};

inline constexpr double kCrossRatioStep = 0.05;

struct LayeredAnalysis {
  std::vector<LayerSpectrum> layers;  // each layer in its order, then the union
  std::vector<CrossHistogram> cross;  // every ordered pair a != b
};

// REQUIRES: world.layers(); each set is that world's (or a reseeded copy's) points in `window`,
// with layers. Rejects (INVALID_ARGUMENT, "--rect") a window that is not square, and a layer
// with no point in some set ("--rect": too small for it). `max_frequency` in cycles per window.
// Cost: a periodogram per layer and set, and the cross pairs within 3 D through a grid.
StatusOr<LayeredAnalysis> AnalyseLayers(const std::vector<PlanePoints>& sets, const World& world,
                                        const Rect& window, int max_frequency);

}  // namespace scallop::cli
