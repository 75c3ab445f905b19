// Tone mapping and layout of periodogram pictures (see the header).
#include "client/analysis/periodogram_image.h"

#include <algorithm>
#include <cmath>

namespace scallop::cli {

constexpr int kGap = 8, kMaxPanelPixels = 256;

Image8 RenderPeriodograms(const std::vector<Periodogram>& periodograms) {
  int tallest = 1;
  for (const Periodogram& p : periodograms) tallest = std::max(tallest, p.side());
  const int scale = std::max(1, kMaxPanelPixels / tallest);
  Image8 image;
  image.channels = 1;
  image.height = tallest * scale;
  image.width = -kGap;
  for (const Periodogram& p : periodograms) image.width += p.side() * scale + kGap;
  image.width = std::max(image.width, 1);
  image.pixels.assign(static_cast<size_t>(image.width) * image.height, 255);
  int left = 0;
  for (const Periodogram& p : periodograms) {
    const int side = p.side(), k = p.max_frequency;
    const int top = (tallest - side) * scale / 2;
    for (int row = 0; row < side; ++row) {
      const int ky = k - row;  // row 0 is the top, +ky
      for (int column = 0; column < side; ++column) {
        const int kx = column - k;
        const uint8_t grey =
            (kx == 0 && ky == 0)
                ? 255
                : GreyLevel(10.0 * std::log10(p.At(kx, ky)), kPeriodogramLowDb, kPeriodogramHighDb);
        for (int dy = 0; dy < scale; ++dy) {
          uint8_t* line =
              image.pixels.data() + static_cast<size_t>(top + row * scale + dy) * image.width;
          std::fill_n(line + left + column * scale, scale, grey);
        }
      }
    }
    left += side * scale + kGap;
  }
  return image;
}

}  // namespace scallop::cli
