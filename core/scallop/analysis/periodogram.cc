// Periodogram by cubic B-spline gridding and FFTW (see periodogram.h for the
// method and its error bound).
#include "scallop/analysis/periodogram.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <numbers>
#include <string>

namespace scallop {
namespace {

// FFTW's planner keeps global state and is not thread-safe; execution is.
std::mutex& FftwPlannerMutex() {
  static std::mutex mutex;
  return mutex;
}

struct FftwFree {
  void operator()(void* memory) const { fftw_free(memory); }
};

// The transform of the cubic B-spline at frequency k of an M-cell grid.
double SplineTransform(int k, int grid_size) {
  if (k == 0) return 1.0;
  const double x = std::numbers::pi * k / grid_size;
  const double sinc = std::sin(x) / x;
  return sinc * sinc * sinc * sinc;
}

Status ValidateInput(std::span<const Vec2> points, const Rect& window, int max_frequency) {
  if (max_frequency < 1 || max_frequency > kMaxPeriodogramFrequency) {
    return InvalidArgument("max_frequency: must be in 1.." +
                           std::to_string(kMaxPeriodogramFrequency) + ", got " +
                           std::to_string(max_frequency));
  }
  const double width = window.Width(), height = window.Height();
  if (!std::isfinite(window.x0) || !std::isfinite(window.y0) || !std::isfinite(window.x1) ||
      !std::isfinite(window.y1) || !std::isfinite(width) || !std::isfinite(height) ||
      !(width > 0) || !(height > 0)) {
    return InvalidArgument("window: must be finite with x0 < x1 and y0 < y1");
  }
  // Rounding of x1 - x0 may differ between the axes of a square given by its corners.
  if (std::abs(width - height) > 1e-9 * std::max(width, height)) {
    return InvalidArgument("window: must be square, got " + std::to_string(width) + " x " +
                           std::to_string(height));
  }
  if (points.empty()) return InvalidArgument("points: must not be empty");
  for (size_t i = 0; i < points.size(); ++i) {
    if (!std::isfinite(points[i].x) || !std::isfinite(points[i].y) || !window.Contains(points[i])) {
      return InvalidArgument("points[" + std::to_string(i) +
                             "]: must be finite and inside the half-open window");
    }
  }
  return Status::Ok();
}

}  // namespace

int PeriodogramGridSize(int max_frequency) {
  int size = 64;
  while (size < 8 * max_frequency) size *= 2;
  return size;
}

StatusOr<Periodogram> ComputePeriodogram(std::span<const Vec2> points, const Rect& window,
                                         int max_frequency) {
  if (Status status = ValidateInput(points, window, max_frequency); !status.ok()) return status;
  const int m = PeriodogramGridSize(max_frequency);
  const size_t cells = static_cast<size_t>(m) * m;
  const int half = m / 2 + 1;  // r2c keeps kx in 0..m/2
  std::unique_ptr<double, FftwFree> grid(fftw_alloc_real(cells));
  std::unique_ptr<fftw_complex, FftwFree> spectrum(
      fftw_alloc_complex(static_cast<size_t>(m) * half));
  if (!grid || !spectrum) return Status(StatusCode::kResourceExhausted, "periodogram: no memory");
  std::fill(grid.get(), grid.get() + cells, 0.0);

  // Spread each point over the 4 x 4 cells its cubic B-spline covers. The
  // grid is periodic because exp(-2 pi i k x / L) is, for integer k.
  const double scale_x = m / window.Width(), scale_y = m / window.Height();
  for (const Vec2& p : points) {
    const double tx = (p.x - window.x0) * scale_x, ty = (p.y - window.y0) * scale_y;
    const double fx_floor = std::floor(tx), fy_floor = std::floor(ty);
    const double fx = tx - fx_floor, fy = ty - fy_floor;
    const double wx[4] = {(1 - fx) * (1 - fx) * (1 - fx) / 6,
                          (3 * fx * fx * fx - 6 * fx * fx + 4) / 6,
                          (-3 * fx * fx * fx + 3 * fx * fx + 3 * fx + 1) / 6, fx * fx * fx / 6};
    const double wy[4] = {(1 - fy) * (1 - fy) * (1 - fy) / 6,
                          (3 * fy * fy * fy - 6 * fy * fy + 4) / 6,
                          (-3 * fy * fy * fy + 3 * fy * fy + 3 * fy + 1) / 6, fy * fy * fy / 6};
    const int ix = static_cast<int>(fx_floor), iy = static_cast<int>(fy_floor);
    for (int b = 0; b < 4; ++b) {
      const int row = ((iy + b - 1) % m + m) % m;
      double* grid_row = grid.get() + static_cast<size_t>(row) * m;
      for (int a = 0; a < 4; ++a) grid_row[((ix + a - 1) % m + m) % m] += wx[a] * wy[b];
    }
  }

  fftw_plan plan;
  {
    std::lock_guard<std::mutex> lock(FftwPlannerMutex());
    plan = fftw_plan_dft_r2c_2d(m, m, grid.get(), spectrum.get(), FFTW_ESTIMATE);
  }
  if (plan == nullptr) return Status(StatusCode::kInternal, "periodogram: FFTW planning failed");
  fftw_execute(plan);
  {
    std::lock_guard<std::mutex> lock(FftwPlannerMutex());
    fftw_destroy_plan(plan);
  }

  Periodogram result;
  result.max_frequency = max_frequency;
  result.set_count = 1;
  result.point_count = static_cast<int64_t>(points.size());
  const int side = result.side();
  result.power.assign(static_cast<size_t>(side) * side, 0.0);
  const double n = static_cast<double>(points.size());
  for (int ky = -max_frequency; ky <= max_frequency; ++ky) {
    for (int kx = -max_frequency; kx <= max_frequency; ++kx) {
      // A real grid's transform is Hermitian: the coefficient at -k is the
      // conjugate of the one at k, with the same power.
      const int sign = kx < 0 ? -1 : 1;
      const int row = ((sign * ky) % m + m) % m, column = sign * kx;
      const fftw_complex& c = spectrum.get()[static_cast<size_t>(row) * half + column];
      const double deconvolve = SplineTransform(kx, m) * SplineTransform(ky, m);
      const double re = c[0] / deconvolve, im = c[1] / deconvolve;
      result.power[static_cast<size_t>(ky + max_frequency) * side + (kx + max_frequency)] =
          (re * re + im * im) / n;
    }
  }
  return result;
}

Status PeriodogramAverage::Add(const Periodogram& periodogram) {
  if (periodogram.set_count < 1 ||
      periodogram.power.size() != static_cast<size_t>(periodogram.side()) * periodogram.side()) {
    return InvalidArgument("periodogram: empty (set_count < 1 or power of the wrong size)");
  }
  if (sum_.set_count == 0) {
    sum_.max_frequency = periodogram.max_frequency;
    sum_.power.assign(periodogram.power.size(), 0.0);
  } else if (periodogram.max_frequency != sum_.max_frequency) {
    return InvalidArgument("periodogram.max_frequency: must equal the first one's, " +
                           std::to_string(sum_.max_frequency) + ", got " +
                           std::to_string(periodogram.max_frequency));
  }
  const double weight = periodogram.set_count;
  for (size_t i = 0; i < sum_.power.size(); ++i) sum_.power[i] += weight * periodogram.power[i];
  sum_.set_count += periodogram.set_count;
  sum_.point_count += periodogram.point_count;
  return Status::Ok();
}

StatusOr<Periodogram> PeriodogramAverage::Mean() const {
  if (sum_.set_count == 0) return InvalidArgument("periodogram average: no set added");
  Periodogram mean = sum_;
  for (double& value : mean.power) value /= mean.set_count;
  return mean;
}

}  // namespace scallop
