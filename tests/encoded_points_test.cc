// The compact point encodings (docs/wire.md) against the packed arrays they
// replace: for random rectangles of several worlds (A1, A2, A3 and a noise
// radius field, whose ids have a wider index), at the origin, at negative
// and at large coordinates (1e9 d) and near the precision limit, exact mode
// decodes to the packed arrays' doubles and ids bit for bit, and quantised
// mode to the same ids with every coordinate within its stated bound. The
// codec's edges are planted by hand (-0.0, the largest double of a region,
// the outermost regions, scattered indices), malformed messages are refused
// naming their field, and a corrupted byte is shown to be caught.
#include "encoded_points.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "scallop/random/rng.h"
#include "tests/field_test_fields.h"
#include "tests/quantised_bound.h"
#include "tests/test_worlds.h"

namespace scallop {
namespace {

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

v1::Points Encode(const PlanePoints& points, const World& world, PointEncoding encoding) {
  v1::Points message;
  AppendPoints(points, 0, points.ids.size(), message, world, encoding);
  return message;
}

PlanePoints Decode(const v1::Points& message, std::vector<double>* radii = nullptr) {
  PlanePoints points;
  const Status status = ReadPoints(message, points, radii);
  EXPECT_TRUE(status.ok()) << status.message();
  return points;
}

// How many points differ from `expected` in id or in a coordinate's bits.
size_t BitDifferences(const PlanePoints& expected, const PlanePoints& actual) {
  if (expected.ids.size() != actual.ids.size()) return std::max(expected.ids.size(), size_t{1});
  size_t differences = 0;
  for (size_t k = 0; k < expected.ids.size(); ++k) {
    if (expected.ids[k] != actual.ids[k] ||
        !SameBits(expected.positions[k].x, actual.positions[k].x) ||
        !SameBits(expected.positions[k].y, actual.positions[k].y)) {
      ++differences;
    }
  }
  return differences;
}

struct WorldCase {
  const char* name;
  World world;
  double extent;  // largest rectangle side, in units of d
};

std::vector<WorldCase> Worlds() {
  WorldSpec field{.seed = 5, .algorithm = WorldAlgorithm::kA3};
  field.radius_field = field_test::NoiseField(5, 1.0, 5.0).spec();
  return {
      {"a3 d=1", ValidWorld({.seed = 7, .min_distance = 1, .algorithm = WorldAlgorithm::kA3}), 60},
      {"a1 d=0.5",
       ValidWorld(
           {.seed = 11, .min_distance = 0.5, .algorithm = WorldAlgorithm::kA1, .density = 1.2}),
       50},
      {"a2 d=3",
       ValidWorld({.seed = 3, .min_distance = 3, .algorithm = WorldAlgorithm::kA2, .density = 1.5}),
       50},
      {"noise field 1..5", ValidWorld(field), 70},
  };
}

// Where rectangles are put, in units of d: the origin (whose regions hold
// -0.0 and the widest exact offsets), negative, 1e6, +-1e9 and near 2^32.
constexpr double kAnchors[][2] = {{0, 0},
                                  {-37, -5},
                                  {1e6, -3e5},
                                  {1e9, -1e9},
                                  {-1e9, 1e9},
                                  {-2e9, 0},
                                  {4294967000.0, -4294967000.0}};

TEST(EncodedPointsTest, ExactDecodesToThePackedArraysBitForBitAndQuantisedWithinItsBound) {
  constexpr uint64_t kSeed = 0x5eed'23;
  Rng dice(kSeed);
  PlaneEngine engine({.cache_bytes = 64 << 20, .threads = 1});
  for (const WorldCase& c : Worlds()) {
    const double d = c.world.min_distance();
    const double side = RegionLayout(c.world).side();
    size_t checked = 0, exact_bytes = 0, quantised_bytes = 0, packed_bytes = 0;
    double worst_error_in_d = 0;
    for (const auto& anchor : kAnchors) {
      for (int n = 0; n < 3; ++n) {
        const double w = dice.Uniform(1, c.extent), h = dice.Uniform(1, c.extent);
        const double x0 = (anchor[0] + dice.Uniform(-c.extent, c.extent)) * d;
        const double y0 = (anchor[1] + dice.Uniform(-c.extent, c.extent)) * d;
        const Rect rect{x0, y0, x0 + w * d, y0 + h * d};
        SCOPED_TRACE(std::string(c.name) + " rect " + std::to_string(rect.x0) + "," +
                     std::to_string(rect.y0) + "," + std::to_string(rect.x1) + "," +
                     std::to_string(rect.y1) + " (dice seed " + std::to_string(kSeed) + ")");
        StatusOr<PlanePoints> points = engine.Points(c.world, rect);
        ASSERT_TRUE(points.ok()) << points.status().message();
        const v1::Points packed = Encode(*points, c.world, PointEncoding::kPacked);
        const v1::Points exact = Encode(*points, c.world, PointEncoding::kExact);
        const v1::Points quantised = Encode(*points, c.world, PointEncoding::kQuantised);
        ASSERT_TRUE(exact.has_encoded() && exact.xs().empty() && exact.ids().empty());
        // The oracle is the packed message as old clients read it.
        const PlanePoints from_packed = Decode(packed);
        std::vector<double> exact_radii, packed_radii;
        Decode(packed, &packed_radii);
        EXPECT_EQ(BitDifferences(from_packed, Decode(exact, &exact_radii)), 0u);
        EXPECT_EQ(exact_radii, packed_radii);
        const PlanePoints rounded = Decode(quantised);
        ASSERT_EQ(rounded.ids, from_packed.ids);
        const RegionLayout layout(c.world);
        for (size_t k = 0; k < rounded.ids.size(); ++k) {
          const Vec2 truth = from_packed.positions[k], got = rounded.positions[k];
          EXPECT_LE(std::fabs(got.x - truth.x), QuantisedBound(truth.x, side)) << k;
          EXPECT_LE(std::fabs(got.y - truth.y), QuantisedBound(truth.y, side)) << k;
          // A cell's centre lies inside its region, so the region is kept.
          EXPECT_EQ(layout.RegionOf(got.x, got.y), layout.RegionOf(truth.x, truth.y)) << k;
          worst_error_in_d = std::max(
              {worst_error_in_d, std::fabs(got.x - truth.x) / d, std::fabs(got.y - truth.y) / d});
        }
        // Bytes of positions and ids: a field world's radii are 8 bytes a
        // point in every encoding.
        const auto size = [](const v1::Points& m) {
          return m.ByteSizeLong() - 8 * static_cast<size_t>(m.radii_size());
        };
        if (points->ids.size() >= 100) {
          EXPECT_LE(size(quantised), 8 * points->ids.size());
        }
        checked += points->ids.size();
        packed_bytes += size(packed);
        exact_bytes += size(exact);
        quantised_bytes += size(quantised);
      }
    }
    ASSERT_GT(checked, 1500u) << c.name;
    // The bound is tight: some coordinate comes near half a cell.
    EXPECT_GT(worst_error_in_d * d, std::ldexp(side, -18)) << c.name;
    const auto per_point = [&](size_t bytes) { return static_cast<double>(bytes) / checked; };
    std::printf(
        "%-18s %7zu points: packed %.2f, exact %.2f, quantised %.2f bytes a point "
        "(radii aside); worst quantised error %.3g d\n",
        c.name, checked, per_point(packed_bytes), per_point(exact_bytes),
        per_point(quantised_bytes), worst_error_in_d);
  }
}

// One region built by hand, decoded through the message reader.
PlanePoints RoundTrip(PointEncoding encoding, const RegionLayout& layout, RegionKey key,
                      const std::vector<uint32_t>& indices, const std::vector<Vec2>& positions,
                      v1::Points* encoded_out = nullptr) {
  EncodedRegionBuilder builder(encoding, layout, key);
  for (size_t n = 0; n < indices.size(); ++n) builder.Add(indices[n], positions[n]);
  EncodedRegion region = std::move(builder).Take();
  v1::Points message;
  v1::EncodedPoints& encoded = *message.mutable_encoded();
  encoded.set_encoding(PointEncodingToMessage(encoding));
  encoded.set_region_side(layout.side());
  encoded.set_id_index_bits(static_cast<uint32_t>(layout.point_id_index_bits()));
  v1::EncodedRegion& r = *encoded.add_regions();
  r.set_i(key.i);
  r.set_j(key.j);
  r.mutable_index_runs()->Add(region.index_runs.begin(), region.index_runs.end());
  r.set_x_offset_bytes(static_cast<uint32_t>(region.x_offset_bytes));
  r.set_y_offset_bytes(static_cast<uint32_t>(region.y_offset_bytes));
  r.set_x_offsets(region.x_offsets);
  r.set_y_offsets(region.y_offsets);
  if (encoded_out != nullptr) *encoded_out = message;
  return Decode(message);
}

TEST(EncodedPointsTest, ExactKeepsTheEdgesOfRegions) {
  const RegionLayout layout(0.75);  // S = 12, not a power of two
  const double S = layout.side();
  const double inf = std::numeric_limits<double>::infinity();
  const double denorm = std::numeric_limits<double>::denorm_min();
  struct Case {
    RegionKey key;
    std::vector<Vec2> positions;
  };
  const int64_t last = layout.regions_per_half_axis() - 1;
  const Case cases[] = {
      // Region (0, 0): -0.0 and +0.0 are different doubles; the smallest
      // subnormal; the largest double below S.
      {{0, 0}, {{-0.0, 0.0}, {0.0, -0.0}, {denorm, std::nextafter(S, 0)}, {S / 3, 1e-300}}},
      // Region (-1, -1): its low edge, and the negative double nearest 0.
      {{-1, -1}, {{-S, -denorm}, {-denorm, -S}, {std::nextafter(-S, 0), -S / 7}}},
      // The outermost regions of the precision range.
      {{last, -last - 1},
       {{layout.RegionRect({last, 0}).x0, layout.RegionRect({0, -last - 1}).y0},
        {std::nextafter(layout.RegionRect({last, 0}).x1, -inf),
         std::nextafter(layout.RegionRect({0, -last - 1}).y1, -inf)}}},
      // A region spanning two binades: [120, 132) holds 128.
      {{10, 2},
       {{120, 24},
        {std::nextafter(132.0, 0), 35.9},
        {128, std::nextafter(24.0, 99)},
        {std::nextafter(128.0, 0), 30}}},
  };
  for (const Case& c : cases) {
    std::vector<uint32_t> indices;
    PlanePoints expected;
    for (size_t n = 0; n < c.positions.size(); ++n) {
      // Scattered indices: skips of 0, 1 and more, up to the last index.
      const uint32_t index = n + 1 == c.positions.size() ? 1023 : static_cast<uint32_t>(n * n);
      indices.push_back(index);
      expected.positions.push_back(c.positions[n]);
      expected.ids.push_back(EncodePointId(c.key, index));
    }
    EXPECT_EQ(BitDifferences(expected,
                             RoundTrip(PointEncoding::kExact, layout, c.key, indices, c.positions)),
              0u)
        << "region " << c.key.i << "," << c.key.j;
  }
}

TEST(EncodedPointsTest, OrderedBitsCountsTheDoublesBetween) {
  Rng dice(23);
  for (int n = 0; n < 100000; ++n) {
    // Random bit patterns: every binade, subnormals and both signs.
    double value = std::bit_cast<double>(dice.NextBits());
    if (!std::isfinite(value)) continue;
    const double next = std::nextafter(value, std::numeric_limits<double>::infinity());
    ASSERT_TRUE(SameBits(FromOrderedBits(OrderedBits(value)), value)) << value;
    if (SameBits(value, -0.0)) continue;  // nextafter(-0.0) is the smallest subnormal
    ASSERT_EQ(OrderedBits(next), OrderedBits(value) + 1) << value;
  }
  EXPECT_EQ(OrderedBits(0.0), OrderedBits(-0.0) + 1);
  EXPECT_EQ(OrderedBits(std::numeric_limits<double>::denorm_min()), OrderedBits(0.0) + 1);
}

TEST(EncodedPointsTest, ExactOffsetWidthFollowsTheDistanceFromTheOrigin) {
  const RegionLayout layout(1.0);  // S = 16
  EXPECT_EQ(ExactOffsetBytes(layout, 0), 8);
  EXPECT_EQ(ExactOffsetBytes(layout, -1), 8);        // [-16, 0): every negative double above -16
  EXPECT_EQ(ExactOffsetBytes(layout, 1), 7);         // [16, 32): 2^52 doubles
  EXPECT_EQ(ExactOffsetBytes(layout, 62500), 5);     // 1e6: ulp 2^-33, 2^37 doubles
  EXPECT_EQ(ExactOffsetBytes(layout, 62500000), 4);  // 1e9: ulp 2^-23, 2^27 doubles
  // [-2^32, -2^32 + 16): -2^32 and 2^25 - 1 doubles of ulp 2^-21 above it.
  EXPECT_EQ(ExactOffsetBytes(layout, -(int64_t{1} << 28)), 4);
}

TEST(EncodedPointsTest, ACorruptedOffsetIsSeen) {
  // The comparison above must be able to fail: flip one bit of one offset.
  const World world = ValidWorld({.seed = 7, .min_distance = 1, .algorithm = WorldAlgorithm::kA3});
  PlaneEngine engine({.threads = 1});
  StatusOr<PlanePoints> points = engine.Points(world, {1e9, -1e9, 1e9 + 40, -1e9 + 40});
  ASSERT_TRUE(points.ok());
  v1::Points exact = Encode(*points, world, PointEncoding::kExact);
  ASSERT_EQ(BitDifferences(*points, Decode(exact)), 0u);
  std::string& offsets = *exact.mutable_encoded()->mutable_regions(1)->mutable_y_offsets();
  offsets[5] = static_cast<char>(offsets[5] ^ 0x01);
  EXPECT_EQ(BitDifferences(*points, Decode(exact)), 1u);
}

TEST(EncodedPointsTest, MalformedMessagesAreRefusedNamingTheField) {
  const RegionLayout layout(1.0);
  v1::Points good;
  RoundTrip(PointEncoding::kExact, layout, {3, -2}, {0, 1, 5}, {{50, -30}, {51, -31}, {60, -20}},
            &good);
  struct Case {
    const char* field;
    void (*spoil)(v1::Points&);
  };
  const Case cases[] = {
      {"encoded.encoding",
       [](v1::Points& m) { m.mutable_encoded()->set_encoding(v1::POINT_ENCODING_PACKED); }},
      {"encoded.encoding",
       [](v1::Points& m) { m.mutable_encoded()->set_encoding(static_cast<v1::PointEncoding>(9)); }},
      {"encoded.region_side", [](v1::Points& m) { m.mutable_encoded()->set_region_side(-1); }},
      {"encoded.region_side",
       [](v1::Points& m) { m.mutable_encoded()->set_region_side(std::nan("")); }},
      {"encoded.id_index_bits", [](v1::Points& m) { m.mutable_encoded()->set_id_index_bits(9); }},
      {"encoded.id_index_bits",
       [](v1::Points& m) { m.mutable_encoded()->set_id_index_bits(1u << 31); }},
      {"encoded.regions[0].index_runs",
       [](v1::Points& m) { m.mutable_encoded()->mutable_regions(0)->add_index_runs(1); }},
      {"encoded.regions[0].index_runs",  // the last index would be 1024
       [](v1::Points& m) { m.mutable_encoded()->mutable_regions(0)->set_index_runs(2, 1022); }},
      {"encoded.regions[0].index_runs",  // counts that would overflow 32 bits
       [](v1::Points& m) {
         m.mutable_encoded()->mutable_regions(0)->set_index_runs(1, 0xffffffff);
       }},
      {"encoded.regions[0].x_offset_bytes",
       [](v1::Points& m) { m.mutable_encoded()->mutable_regions(0)->set_x_offset_bytes(0); }},
      {"encoded.regions[0].y_offset_bytes",
       [](v1::Points& m) { m.mutable_encoded()->mutable_regions(0)->set_y_offset_bytes(9); }},
      {"encoded.regions[0].y_offsets",
       [](v1::Points& m) {
         m.mutable_encoded()->mutable_regions(0)->mutable_y_offsets()->pop_back();
       }},
      {"encoded.regions[1].x_offsets",  // a good region, then a bad one: neither is kept
       [](v1::Points& m) {
         v1::EncodedRegion& copy = *m.mutable_encoded()->add_regions();
         copy = m.encoded().regions(0);
         copy.mutable_x_offsets()->pop_back();
       }},
      {"points: encoded and the packed", [](v1::Points& m) { m.add_xs(1); }},
      {"points: radii", [](v1::Points& m) { m.add_radii(1); }},
  };
  for (const Case& c : cases) {
    v1::Points bad = good;
    c.spoil(bad);
    PlanePoints points;
    points.ids.push_back(42);  // earlier points stay as they were
    points.positions.push_back({1, 2});
    const Status status = ReadPoints(bad, points);
    EXPECT_EQ(status.code(), StatusCode::kInvalidArgument) << c.field;
    EXPECT_EQ(status.message().rfind(c.field, 0), 0u) << status.message();
    EXPECT_EQ(points.ids.size(), 1u) << c.field;
  }
}

TEST(EncodedPointsTest, RequestEncodingsAreCheckedByName) {
  EXPECT_EQ(*PointEncodingFromMessage(v1::POINT_ENCODING_UNSPECIFIED), PointEncoding::kPacked);
  EXPECT_EQ(*PointEncodingFromMessage(v1::POINT_ENCODING_PACKED), PointEncoding::kPacked);
  EXPECT_EQ(*PointEncodingFromMessage(v1::POINT_ENCODING_EXACT), PointEncoding::kExact);
  EXPECT_EQ(*PointEncodingFromMessage(v1::POINT_ENCODING_QUANTISED), PointEncoding::kQuantised);
  const StatusOr<PointEncoding> unknown = PointEncodingFromMessage(4);
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.status().message().rfind("encoding: ", 0), 0u);
}

}  // namespace
}  // namespace scallop
