// Statistics and a picture of radius-field point sets, judged against the field.
#include "client/analysis/field_analysis.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace scallop::cli {
namespace {

constexpr int kAreaGrid = 256;

int BandOf(double r, const RadiusField& field, int bands) {
  if (field.r_max() <= field.r_min()) return 0;
  const double t = std::log(r / field.r_min()) / std::log(field.r_max() / field.r_min());
  return std::clamp(static_cast<int>(t * bands), 0, bands - 1);
}

// The points filed in square cells of side `side`, for neighbour searches.
class CellIndex {
 public:
  CellIndex(std::span<const Vec2> points, double side) : points_(points), side_(side) {
    for (size_t k = 0; k < points.size(); ++k) cells_[Key(points[k])].push_back(k);
  }
  // Calls f(index) for every point within `reach` cells of p's.
  template <typename F>
  void Around(Vec2 p, int reach, F f) const {
    const int64_t ci = Cell(p.x), cj = Cell(p.y);
    for (int64_t j = cj - reach; j <= cj + reach; ++j) {
      for (int64_t i = ci - reach; i <= ci + reach; ++i) {
        const auto found = cells_.find(Pack(i, j));
        if (found == cells_.end()) continue;
        for (size_t k : found->second) f(k);
      }
    }
  }

 private:
  int64_t Cell(double v) const { return static_cast<int64_t>(std::floor(v / side_)); }
  static uint64_t Pack(int64_t i, int64_t j) {
    return (static_cast<uint64_t>(i) << 32) ^ static_cast<uint32_t>(j);
  }
  uint64_t Key(Vec2 p) const { return Pack(Cell(p.x), Cell(p.y)); }

  std::span<const Vec2> points_;
  double side_;
  std::unordered_map<uint64_t, std::vector<size_t>> cells_;
};

}  // namespace

double FieldBand::Rho() const {
  return area > 0 ? std::sqrt(std::sqrt(3.0) / 2 * sum_r2 / area) : 0;
}

void AddFieldStatistics(std::span<const Vec2> points, const RadiusField& field, const Rect& window,
                        int bands, FieldStatistics& total) {
  if (total.bands.empty()) {
    const double ratio = field.r_max() / field.r_min();
    // Assigned, not designated: GCC asks a designated initializer for every member.
    total.bands.resize(bands);
    for (int b = 0; b < bands; ++b) {
      total.bands[b].r_lo = field.r_min() * std::pow(ratio, double(b) / bands);
      total.bands[b].r_hi = field.r_min() * std::pow(ratio, double(b + 1) / bands);
    }
    total.all.r_lo = field.r_min();
    total.all.r_hi = field.r_max();
    total.smallest_ratio = std::numeric_limits<double>::infinity();
    total.pair_ratio_counts.assign(static_cast<size_t>(kPairRatioLimit / kPairRatioStep), 0.0);
  }
  const double cell_area = window.Area() / (kAreaGrid * kAreaGrid);
  for (int j = 0; j < kAreaGrid; ++j) {
    for (int i = 0; i < kAreaGrid; ++i) {
      const Vec2 x{window.x0 + (i + 0.5) * window.Width() / kAreaGrid,
                   window.y0 + (j + 0.5) * window.Height() / kAreaGrid};
      if (field.IsMasked(x)) continue;
      total.bands[BandOf(field.Evaluate(x), field, bands)].area += cell_area;
      total.all.area += cell_area;
    }
  }
  std::vector<double> radius(points.size());
  for (size_t k = 0; k < points.size(); ++k) radius[k] = field.Evaluate(points[k]);
  const double r_max = field.r_max();
  const CellIndex index(points, r_max);
  // The spectrum's neighbours reach kCutoff R(p): cells between r_min and r_max keep both the
  // cells a small R scans and the points a large R's cells hold moderate.
  const double spectrum_cell = std::sqrt(field.r_min() * r_max);
  const CellIndex spectrum_index(points, spectrum_cell);
  // Pair ratios below kPairRatioLimit need neighbours within kPairRatioLimit r_max.
  const int reach = static_cast<int>(std::ceil(kPairRatioLimit));
  const double margin = kPairRatioLimit * r_max;
  for (size_t k = 0; k < points.size(); ++k) {
    const Vec2 p = points[k];
    FieldBand& band = total.bands[BandOf(radius[k], field, bands)];
    for (FieldBand* b : {&band, &total.all}) {
      ++b->points;
      b->sum_r2 += radius[k] * radius[k];
    }
    const bool inside = p.x - window.x0 >= margin && window.x1 - p.x >= margin &&
                        p.y - window.y0 >= margin && window.y1 - p.y >= margin;
    double nearest = std::numeric_limits<double>::infinity();
    index.Around(p, reach, [&](size_t m) {
      if (m == k) return;
      // The rule's own expression decides a conflict (dx^2 + dy^2 < m^2, as the sampler and
      // the verifier evaluate it): the ratio below can round to 1 - 2^-53 for a pair at exactly
      // the spacing, which the rule allows.
      const double dx = points[m].x - p.x, dy = points[m].y - p.y;
      const double spacing = std::max(radius[k], radius[m]);
      const double ratio = std::hypot(dx, dy) / spacing;
      nearest = std::min(nearest, ratio);
      if (m > k) {
        total.smallest_ratio = std::min(total.smallest_ratio, ratio);
        if (dx * dx + dy * dy < spacing * spacing) ++total.conflicts;
      }
      if (inside && ratio < kPairRatioLimit) {
        total.pair_ratio_counts[static_cast<size_t>(ratio / kPairRatioStep)] += 1;
      }
    });
    if (inside) ++total.pair_ratio_points;
    const double reach_spectrum = PairDistanceHistogram::kCutoff * radius[k];
    if (p.x - window.x0 >= reach_spectrum && window.x1 - p.x >= reach_spectrum &&
        p.y - window.y0 >= reach_spectrum && window.y1 - p.y >= reach_spectrum) {
      ++band.pairs.points;
      ++total.all.pairs.points;
      spectrum_index.Around(
          p, static_cast<int>(std::ceil(reach_spectrum / spectrum_cell)), [&](size_t m) {
            if (m == k) return;
            const double s = std::hypot(points[m].x - p.x, points[m].y - p.y) / radius[k];
            band.pairs.AddNeighbour(s);
            total.all.pairs.AddNeighbour(s);
          });
    }
    if (inside && std::isfinite(nearest)) {
      for (FieldBand* b : {&band, &total.all}) {
        ++b->nn_points;
        b->nn_ratio_sum += nearest;
      }
    }
  }
}

std::vector<double> FieldStatistics::PairRatioPerPoint() const {
  std::vector<double> per_point(pair_ratio_counts.size(), 0.0);
  if (pair_ratio_points == 0) return per_point;
  for (size_t b = 0; b < per_point.size(); ++b) {
    per_point[b] = pair_ratio_counts[b] / static_cast<double>(pair_ratio_points);
  }
  return per_point;
}

BandSpectrum SpectrumOf(const FieldBand& band) {
  BandSpectrum spectrum;
  // From 0.2 cycles per R: below about 1 / kCutoff the pairs' reach cannot resolve the
  // spectrum, and where the field varies the density estimate's error dominates there.
  for (int k = 10; k <= 150; ++k) spectrum.frequency.push_back(0.02 * k);
  spectrum.power = PairRadialSpectrum(band.pairs, spectrum.frequency);
  double low_sum = 0;
  int low_count = 0;
  for (size_t k = 0; k < spectrum.frequency.size(); ++k) {
    if (spectrum.frequency[k] < 0.5) low_sum += spectrum.power[k], ++low_count;
    if (spectrum.power[k] > spectrum.peak_power) {
      spectrum.peak_power = spectrum.power[k];
      spectrum.peak_frequency = spectrum.frequency[k];
    }
  }
  spectrum.low_power = low_count > 0 ? low_sum / low_count : 0;
  return spectrum;
}

Image8 RenderPointsOverField(std::span<const Vec2> points, const RadiusField& field,
                             const Rect& window, int size) {
  const double scale = size / std::max(window.Width(), window.Height());
  Image8 image;
  image.width = std::max(1, static_cast<int>(std::lround(window.Width() * scale)));
  image.height = std::max(1, static_cast<int>(std::lround(window.Height() * scale)));
  image.channels = 3;
  image.pixels.resize(static_cast<size_t>(image.width) * image.height * 3);
  auto put = [&](int i, int j, uint8_t r, uint8_t g, uint8_t b) {
    if (i < 0 || j < 0 || i >= image.width || j >= image.height) return;
    uint8_t* pixel =
        &image.pixels[(static_cast<size_t>(image.height - 1 - j) * image.width + i) * 3];
    pixel[0] = r, pixel[1] = g, pixel[2] = b;
  };
  for (int j = 0; j < image.height; ++j) {
    for (int i = 0; i < image.width; ++i) {
      const Vec2 x{window.x0 + (i + 0.5) / scale, window.y0 + (j + 0.5) / scale};
      if (field.IsMasked(x)) {
        put(i, j, 110, 30, 30);
        continue;
      }
      // Light where R is large (sparse), darker where points crowd.
      const uint8_t grey = static_cast<uint8_t>(
          120 + GreyLevel(field.Evaluate(x), field.r_min(), field.r_max()) * 120 / 255);
      put(i, j, grey, grey, grey);
    }
  }
  for (const Vec2& p : points) {
    const double cx = (p.x - window.x0) * scale, cy = (p.y - window.y0) * scale;
    const double ring = field.Evaluate(p) / 2 * scale;
    const int reach = static_cast<int>(std::ceil(ring + 1));
    for (int dj = -reach; dj <= reach; ++dj) {
      for (int di = -reach; di <= reach; ++di) {
        const int i = static_cast<int>(std::floor(cx)) + di,
                  j = static_cast<int>(std::floor(cy)) + dj;
        const double distance = std::hypot(i + 0.5 - cx, j + 0.5 - cy);
        if (distance <= std::max(1.0, ring / 4)) {
          put(i, j, 20, 40, 130);
        } else if (std::abs(distance - ring) <= 0.5) {
          put(i, j, 60, 90, 170);
        }
      }
    }
  }
  return image;
}

}  // namespace scallop::cli
