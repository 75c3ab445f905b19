// Periodograms as a picture for `scallop analyze --png`: each tone-mapped to
// grey on a decibel scale, placed side by side.
#pragma once

#include <vector>

#include "scallop/analysis/periodogram.h"
#include "scallop/image/png_image.h"

namespace scallop::cli {

// The decibel range mapped to black..white: -15 dB (a thirtieth of white
// noise's power, below the low-energy annulus of every sampler we have) to
// +5 dB (about 3 times it, above the peak of every maximal sampler). Fixed rather than fitted per
// image so that pictures of different methods compare by eye, as in Lagae & Dutre.
inline constexpr double kPeriodogramLowDb = -15.0, kPeriodogramHighDb = 5.0;

// The periodograms side by side, left to right, 8 white pixels apart, with
// +ky up and the DC term (power N) drawn white. Each frequency is a square
// of pixels; the size of that square is the same for every panel, the
// largest that keeps the tallest panel within 256 pixels (at least 1). Grey level:
// GreyLevel(10 log10(power), kPeriodogramLowDb, kPeriodogramHighDb).
// Panels may differ in max_frequency; smaller ones are centred vertically.
// REQUIRES: at least one periodogram, each with a consistent power array.
// O(pixels).
Image8 RenderPeriodograms(const std::vector<Periodogram>& periodograms);

}  // namespace scallop::cli
