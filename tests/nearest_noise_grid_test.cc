// Noise images and cell values: every channel of EvaluateNoiseGrid equals
// the lookup at the documented sample coordinates (and so, through
// nearest_lookup_test, the brute force); grids are validated field by
// field; the cell value is pinned, in [0, 1), and uniform.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "scallop/noise/cell_value.h"
#include "scallop/noise/noise_grid.h"
#include "tests/nearest_oracle.h"
#include "tests/test_worlds.h"

namespace scallop::testing {
namespace {

constexpr NoiseChannel kChannels[] = {NoiseChannel::kF1, NoiseChannel::kF2,
                                      NoiseChannel::kF2MinusF1, NoiseChannel::kId,
                                      NoiseChannel::kCellValue};

TEST(NoiseGridTest, EveryChannelIsTheLookupAtTheSamplePositions) {
  PlaneEngine engine({.threads = 1});
  NearestLookup lookup(engine);
  const World world = ValidWorld({.seed = 12, .min_distance = 0.8});
  // An odd step and an origin off the seams, so samples land everywhere;
  // 67,900 samples, so that the image takes two batches of whole rows.
  const NoiseGridSpec base{
      .origin = {-13.37, 21.1}, .step = 0.173, .width = 97, .height = 700, .channel = {}};
  std::vector<Vec2> positions;
  for (int r = 0; r < base.height; ++r) {
    for (int c = 0; c < base.width; ++c) {
      positions.push_back({base.origin.x + c * base.step, base.origin.y + r * base.step});
    }
  }
  std::vector<NearestPoint> expected(positions.size());
  ASSERT_TRUE(lookup.Nearest(world, positions, expected).ok());
  // Spot-check the expectation itself against the brute force.
  for (size_t k = 0; k < positions.size(); k += 1001) {
    EXPECT_TRUE(SameNearest(OracleNearest(engine, world, positions[k]), expected[k]));
  }
  for (NoiseChannel channel : kChannels) {
    NoiseGridSpec spec = base;
    spec.channel = channel;
    StatusOr<NoiseImage> image = EvaluateNoiseGrid(lookup, world, spec, 1 << 20);
    ASSERT_TRUE(image.ok()) << image.status().message();
    ASSERT_EQ(image->width, spec.width);
    ASSERT_EQ(image->height, spec.height);
    const bool ids = channel == NoiseChannel::kId;
    ASSERT_EQ(image->ids.size(), ids ? positions.size() : 0u);
    ASSERT_EQ(image->values.size(), ids ? 0u : positions.size());
    int wrong = 0;
    for (size_t k = 0; k < positions.size(); ++k) {
      const NearestPoint& n = expected[k];
      switch (channel) {
        case NoiseChannel::kF1:
          wrong += !SameBits(image->values[k], n.f1);
          break;
        case NoiseChannel::kF2:
          wrong += !SameBits(image->values[k], n.f2);
          break;
        case NoiseChannel::kF2MinusF1:
          wrong += !SameBits(image->values[k], n.f2 - n.f1);
          break;
        case NoiseChannel::kId:
          wrong += image->ids[k] != n.id;
          break;
        case NoiseChannel::kCellValue:
          wrong += !SameBits(image->values[k], n.cell_value);
          break;
      }
    }
    EXPECT_EQ(wrong, 0) << NoiseChannelName(channel);
    EXPECT_EQ(ParseNoiseChannel(NoiseChannelName(channel)).value(), channel);
  }
}

TEST(NoiseGridTest, RejectsBadGridsNamingTheField) {
  PlaneEngine engine({.threads = 1});
  NearestLookup lookup(engine);
  const World world = ValidWorld({.seed = 1});
  const NoiseGridSpec good{.origin = {0, 0}, .step = 1, .width = 4, .height = 3, .channel = {}};
  EXPECT_TRUE(ValidateNoiseGrid(world, good, 12).ok());
  auto expect = [&](NoiseGridSpec spec, int64_t max_samples, StatusCode code, const char* field) {
    const Status status = ValidateNoiseGrid(world, spec, max_samples);
    EXPECT_EQ(status.code(), code) << field << ": " << status.message();
    EXPECT_EQ(status.message().rfind(field, 0), 0u) << status.message();
    EXPECT_FALSE(EvaluateNoiseGrid(lookup, world, spec, max_samples).ok());
  };
  NoiseGridSpec spec = good;
  expect(spec, 11, StatusCode::kInvalidArgument, "width * height");
  spec.step = 0;
  expect(spec, 12, StatusCode::kInvalidArgument, "step");
  spec = good;
  spec.step = std::nan("");
  expect(spec, 12, StatusCode::kInvalidArgument, "step");
  spec = good;
  spec.width = 0;
  expect(spec, 12, StatusCode::kInvalidArgument, "width");
  spec = good;
  spec.height = -1;
  expect(spec, 12, StatusCode::kInvalidArgument, "height");
  spec = good;
  spec.origin.y = INFINITY;
  expect(spec, 12, StatusCode::kInvalidArgument, "origin_y");
  // The last sample, not the origin, crosses the precision limit.
  spec = good;
  spec.origin.x = 0x1.0p32 - 2.5;
  expect(spec, 12, StatusCode::kOutOfRange, "last sample");
  spec.origin.x = 0x1.0p32 - 3;
  EXPECT_TRUE(ValidateNoiseGrid(world, spec, 12).ok());
  EXPECT_FALSE(ParseNoiseChannel("f3").ok());
}

TEST(CellValueTest, PinnedInRangeAndUniform) {
  // Pinned: the documented formula, (Mix64(id + 0x9e3779b97f4a7c15) >> 11) * 2^-53.
  EXPECT_EQ(CellValue(0), static_cast<double>(Mix64(0x9e3779b97f4a7c15ULL) >> 11) * 0x1.0p-53);
  // SplitMix64's published first output for seed 0 is 0xe220a8397b1dcdaf.
  EXPECT_EQ(CellValue(0), static_cast<double>(0xe220a8397b1dcdafULL >> 11) * 0x1.0p-53);
  constexpr int kBins = 16, kIds = 1 << 16;
  int counts[kBins] = {};
  for (uint64_t id = 0; id < kIds; ++id) {
    const double v = CellValue(id * 1024);  // region-like ids: index 0 of consecutive regions
    ASSERT_GE(v, 0.0);
    ASSERT_LT(v, 1.0);
    ++counts[static_cast<int>(v * kBins)];
  }
  // Chi-square with 15 degrees of freedom: 37.7 is the 0.1% critical value.
  double chi_square = 0;
  for (int count : counts) {
    const double expected = static_cast<double>(kIds) / kBins;
    chi_square += (count - expected) * (count - expected) / expected;
  }
  EXPECT_LT(chi_square, 37.7);
}

}  // namespace
}  // namespace scallop::testing
