// The API's point arrays as scallopd fills them: PointsAppender writes
// through plain pointers into room made up front, so its sizes and contents
// are checked against add_xs()-style appends, on empty and non-empty
// messages, with the room used in full, in part and not at all; a field
// world's radii beside them. And worlds with radius fields through messages
// both ways: field worlds round-trip, plain worlds carry no field.
#include "world_messages.h"

#include <gtest/gtest.h>

#include <vector>

namespace scallop {
namespace {

// The message's points, read back as plain values.
PlanePoints Read(const v1::Points& message) {
  PlanePoints points;
  EXPECT_TRUE(ReadPoints(message, points).ok());
  return points;
}

PlanePoints Sample(size_t count, double shift) {
  PlanePoints points;
  for (size_t k = 0; k < count; ++k) {
    points.positions.push_back(
        {shift + 0.5 * static_cast<double>(k), shift - static_cast<double>(k)});
    points.ids.push_back(1000 + k);
  }
  return points;
}

void ExpectSame(const PlanePoints& a, const PlanePoints& b) {
  ASSERT_EQ(a.ids.size(), b.ids.size());
  for (size_t k = 0; k < a.ids.size(); ++k) {
    EXPECT_EQ(a.positions[k], b.positions[k]) << k;
    EXPECT_EQ(a.ids[k], b.ids[k]) << k;
  }
}

TEST(PointsAppenderTest, AppendsWhatWasGivenAndCutsTheRestOfTheRoom) {
  const PlanePoints earlier = Sample(2, -7.25), later = Sample(5, 3.0);
  for (size_t existing : {size_t{0}, size_t{2}}) {
    for (size_t appended : {size_t{0}, size_t{3}, size_t{5}}) {
      v1::Points message;
      PlanePoints expected;
      for (size_t k = 0; k < existing; ++k) {
        message.add_xs(earlier.positions[k].x);
        message.add_ys(earlier.positions[k].y);
        message.add_ids(earlier.ids[k]);
        expected.positions.push_back(earlier.positions[k]);
        expected.ids.push_back(earlier.ids[k]);
      }
      {
        PointsAppender appender(message, 5);
        for (size_t k = 0; k < appended; ++k) appender.Append(later.positions[k], later.ids[k]);
        EXPECT_EQ(appender.count(), appended);
      }
      for (size_t k = 0; k < appended; ++k) {
        expected.positions.push_back(later.positions[k]);
        expected.ids.push_back(later.ids[k]);
      }
      ASSERT_EQ(message.xs_size(), static_cast<int>(existing + appended));
      ASSERT_EQ(message.ys_size(), message.xs_size());
      ASSERT_EQ(message.ids_size(), message.xs_size());
      ExpectSame(Read(message), expected);
    }
  }
}

TEST(PointsAppenderTest, AppendPointsCopiesTheRange) {
  const PlanePoints points = Sample(6, 1.5);
  v1::Points message;
  AppendPoints(points, 1, 4, message);
  AppendPoints(points, 5, 6, message);
  AppendPoints(points, 2, 2, message);  // empty range
  PlanePoints expected;
  for (size_t k : {1, 2, 3, 5}) {
    expected.positions.push_back(points.positions[k]);
    expected.ids.push_back(points.ids[k]);
  }
  ExpectSame(Read(message), expected);
}

TEST(PointsAppenderTest, FieldWorldsCarryRAtEachPoint) {
  RadiusFieldSpec spec{.kind = RadiusFieldKind::kNoise, .r_min = 1.0, .r_max = 3.0};
  spec.frequency = 0.01;
  const StatusOr<RadiusField> field = RadiusField::Create(spec);
  ASSERT_TRUE(field.ok()) << field.status().message();
  const PlanePoints points = Sample(5, 2.5);
  v1::Points message;
  AppendPoints(points, 0, 2, message);  // a plain world's points: no radii
  EXPECT_EQ(message.radii_size(), 0);
  v1::Points with_radii;
  {
    PointsAppender appender(with_radii, 5, &*field);
    for (size_t k = 0; k < 3; ++k) appender.Append(points.positions[k], points.ids[k]);
  }
  ASSERT_EQ(with_radii.radii_size(), 3);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(with_radii.radii(k), field->Evaluate(points.positions[k])) << k;
  }
  PlanePoints read;
  std::vector<double> radii;
  ASSERT_TRUE(ReadPoints(with_radii, read, &radii).ok());
  EXPECT_EQ(radii, std::vector<double>(with_radii.radii().begin(), with_radii.radii().end()));
  // Planted: one radius too few is a malformed message.
  with_radii.mutable_radii()->RemoveLast();
  EXPECT_FALSE(ReadPoints(with_radii, read, &radii).ok());
}

v1::World NoiseWorldMessage() {
  v1::World message;
  message.set_seed(12);
  message.set_algorithm(v1::ALGORITHM_A3);
  v1::NoiseRadiusField& noise = *message.mutable_radius_field()->mutable_noise();
  noise.set_r_min(0.5);
  noise.set_r_max(2.0);
  noise.set_frequency(0.02);
  noise.set_noise_seed(7);
  return message;
}

TEST(WorldMessagesTest, NoiseWorldRoundTripsWithItsDefaultsFilledIn) {
  const StatusOr<World> world = WorldFromMessage(NoiseWorldMessage());
  ASSERT_TRUE(world.ok()) << world.status().message();
  ASSERT_NE(world->radius_field(), nullptr);
  EXPECT_EQ(world->min_distance(), 0.5);  // normalised to r_min
  EXPECT_EQ(world->max_spacing(), 2.0);
  const v1::World answer = WorldToMessage(*world);
  EXPECT_EQ(answer.min_distance(), 0.5);
  EXPECT_EQ(answer.radius_field().noise().octaves(), 3);
  EXPECT_EQ(answer.radius_field().noise().gain(), 0.5);
  EXPECT_EQ(answer.radius_field().noise().noise_seed(), 7u);
  const StatusOr<World> again = WorldFromMessage(answer);
  ASSERT_TRUE(again.ok()) << again.status().message();
  EXPECT_EQ(*again, *world);
  EXPECT_EQ(again->fingerprint(), world->fingerprint());
  // The field's own seed is part of the world.
  v1::World other = NoiseWorldMessage();
  other.mutable_radius_field()->mutable_noise()->set_noise_seed(8);
  EXPECT_NE(WorldFromMessage(other)->fingerprint(), world->fingerprint());
}

TEST(WorldMessagesTest, RasterWorldNamesItsRasterOnlyWithTheCatalog) {
  RasterCatalog catalog;
  ASSERT_TRUE(
      catalog.Add("ramp", {.width = 3, .height = 1, .bit_depth = 8, .pixels = {1, 2, 3}}).ok());
  v1::World message;
  message.set_seed(3);
  message.set_algorithm(v1::ALGORITHM_A3);
  v1::RasterRadiusField& raster = *message.mutable_radius_field()->mutable_raster();
  raster.set_raster_name("ramp");
  raster.set_pixel_size(2.0);
  raster.set_r_min(1.0);
  raster.set_r_max(2.0);
  // Without the catalog no raster name is known.
  const StatusOr<World> unknown = WorldFromMessage(message);
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.status().message().rfind("world.radius_field.raster.raster_name: ", 0), 0u)
      << unknown.status().message();
  const StatusOr<World> world = WorldFromMessage(message, &catalog);
  ASSERT_TRUE(world.ok()) << world.status().message();
  const v1::World answer = WorldToMessage(*world, &catalog);
  EXPECT_EQ(answer.radius_field().raster().raster_name(), "ramp");
  EXPECT_EQ(answer.radius_field().raster().pixel_hash(), catalog.Find("ramp")->pixel_hash);
  EXPECT_EQ(WorldToMessage(*world).radius_field().raster().raster_name(), "");
}

TEST(WorldMessagesTest, FieldWorldsMustBeA3AndPlainWorldsCarryNoField) {
  v1::World a1 = NoiseWorldMessage();
  a1.set_algorithm(v1::ALGORITHM_A1);
  const StatusOr<World> refused = WorldFromMessage(a1);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().message().rfind("world.algorithm", 0), 0u)
      << refused.status().message();
  v1::World plain = NoiseWorldMessage();
  plain.clear_radius_field();
  plain.set_min_distance(1.0);
  const StatusOr<World> world = WorldFromMessage(plain);
  ASSERT_TRUE(world.ok());
  EXPECT_EQ(world->radius_field(), nullptr);
  EXPECT_FALSE(WorldToMessage(*world).has_radius_field());
  // A field with no kind is refused, not read as "no field".
  v1::World empty = plain;
  empty.mutable_radius_field();
  EXPECT_FALSE(WorldFromMessage(empty).ok());
}

}  // namespace
}  // namespace scallop
