// Radius fields in messages: spec -> message -> spec round trips (noise with defaults, raster by
// name and pixel hash), the raster catalog and its hash, and every bad field planted in an
// otherwise valid message, each refused with INVALID_ARGUMENT naming the message's field.
#include "field_messages.h"

#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "tests/test_png.h"

namespace scallop {
namespace {

// A 4 x 3 8-bit raster whose neighbouring pixels differ by at most 10 levels.
RasterImage GentleImage() {
  RasterImage image;
  image.width = 4;
  image.height = 3;
  image.bit_depth = 8;
  image.pixels = {10, 20, 30, 40, 15, 25, 35, 45, 20, 30, 40, 50};
  return image;
}

RasterCatalog Catalog() {
  RasterCatalog catalog;
  EXPECT_TRUE(catalog.Add("hills", GentleImage()).ok());
  return catalog;
}

v1::RadiusField ValidNoise() {
  v1::RadiusField message;
  v1::NoiseRadiusField& noise = *message.mutable_noise();
  noise.set_r_min(1.0);
  noise.set_r_max(4.0);
  noise.set_frequency(0.01);
  noise.set_octaves(2);
  noise.set_gain(0.75);
  noise.set_noise_seed(99);
  return message;
}

v1::RadiusField ValidRaster() {
  v1::RadiusField message;
  v1::RasterRadiusField& raster = *message.mutable_raster();
  raster.set_raster_name("hills");
  raster.set_origin_x(-3.5);
  raster.set_origin_y(2.0);
  raster.set_pixel_size(8.0);
  raster.set_r_min(1.0);
  raster.set_r_max(2.0);
  return message;
}

// The refusal of `message`: INVALID_ARGUMENT whose text starts with `field` and a colon.
void ExpectRefused(const v1::RadiusField& message, const RasterCatalog& catalog,
                   const std::string& field) {
  const StatusOr<RadiusFieldSpec> spec = RadiusFieldFromMessage(message, catalog);
  ASSERT_FALSE(spec.ok()) << field;
  EXPECT_EQ(spec.status().code(), StatusCode::kInvalidArgument) << spec.status().message();
  EXPECT_EQ(spec.status().message().rfind(field + ":", 0), 0u) << spec.status().message();
}

TEST(FieldMessagesTest, NoiseRoundTripsFieldForField) {
  const RasterCatalog catalog = Catalog();
  const StatusOr<RadiusFieldSpec> spec = RadiusFieldFromMessage(ValidNoise(), catalog);
  ASSERT_TRUE(spec.ok()) << spec.status().message();
  EXPECT_EQ(spec->kind, RadiusFieldKind::kNoise);
  EXPECT_EQ(spec->r_min, 1.0);
  EXPECT_EQ(spec->r_max, 4.0);
  EXPECT_EQ(spec->frequency, 0.01);
  EXPECT_EQ(spec->octaves, 2);
  EXPECT_EQ(spec->gain, 0.75);
  EXPECT_EQ(spec->noise_seed, 99u);
  const v1::RadiusField back = RadiusFieldToMessage(*spec, nullptr);
  EXPECT_EQ(back.SerializeAsString(), ValidNoise().SerializeAsString());
}

TEST(FieldMessagesTest, NoiseZeroOctavesAndGainMeanTheDefaults) {
  v1::RadiusField message = ValidNoise();
  message.mutable_noise()->set_octaves(0);
  message.mutable_noise()->set_gain(0.0);
  const StatusOr<RadiusFieldSpec> spec = RadiusFieldFromMessage(message, Catalog());
  ASSERT_TRUE(spec.ok()) << spec.status().message();
  EXPECT_EQ(spec->octaves, 3);
  EXPECT_EQ(spec->gain, 0.5);
  // Answers carry the defaults explicitly.
  const v1::RadiusField back = RadiusFieldToMessage(*spec, nullptr);
  EXPECT_EQ(back.noise().octaves(), 3);
  EXPECT_EQ(back.noise().gain(), 0.5);
}

TEST(FieldMessagesTest, RasterRoundTripsByNameAndHash) {
  const RasterCatalog catalog = Catalog();
  const NamedRaster* hills = catalog.Find("hills");
  ASSERT_NE(hills, nullptr);
  const StatusOr<RadiusFieldSpec> spec = RadiusFieldFromMessage(ValidRaster(), catalog);
  ASSERT_TRUE(spec.ok()) << spec.status().message();
  EXPECT_EQ(spec->kind, RadiusFieldKind::kRaster);
  EXPECT_EQ(spec->raster, hills->image);  // the catalog's pixels, not a copy
  EXPECT_EQ(spec->raster_origin, (Vec2{-3.5, 2.0}));
  EXPECT_EQ(spec->pixel_size, 8.0);
  EXPECT_EQ(spec->r_min, 1.0);
  EXPECT_EQ(spec->r_max, 2.0);
  EXPECT_EQ(RasterOf(*spec, &catalog), hills);
  EXPECT_EQ(RasterOf(*spec, nullptr), nullptr);

  const v1::RadiusField back = RadiusFieldToMessage(*spec, RasterOf(*spec, &catalog));
  v1::RadiusField expected = ValidRaster();
  expected.mutable_raster()->set_pixel_hash(hills->pixel_hash);
  EXPECT_EQ(back.SerializeAsString(), expected.SerializeAsString());
  // The answer, sent back as a request (hash pinned), reads the same.
  const StatusOr<RadiusFieldSpec> again = RadiusFieldFromMessage(back, catalog);
  ASSERT_TRUE(again.ok()) << again.status().message();
  EXPECT_EQ(again->raster, hills->image);
}

TEST(FieldMessagesTest, ConstantSpecCarriesNoField) {
  RadiusFieldSpec constant;
  EXPECT_EQ(RadiusFieldToMessage(constant, nullptr).kind_case(), v1::RadiusField::KIND_NOT_SET);
}

TEST(FieldMessagesTest, ValidMessagesPassSoEachRefusalBelowIsTheFieldPlantedInIt) {
  EXPECT_TRUE(RadiusFieldFromMessage(ValidNoise(), Catalog()).ok());
  EXPECT_TRUE(RadiusFieldFromMessage(ValidRaster(), Catalog()).ok());
}

TEST(FieldMessagesTest, NoKindIsRefused) {
  ExpectRefused(v1::RadiusField(), Catalog(), "world.radius_field");
}

TEST(FieldMessagesTest, BadNoiseFieldsAreNamed) {
  struct Case {
    void (*plant)(v1::NoiseRadiusField&);
    const char* field;
  };
  const Case cases[] = {
      {[](v1::NoiseRadiusField& n) { n.set_r_min(0.0); }, "r_min"},
      {[](v1::NoiseRadiusField& n) { n.set_r_min(-1.0); }, "r_min"},
      {[](v1::NoiseRadiusField& n) { n.set_r_min(std::numeric_limits<double>::quiet_NaN()); },
       "r_min"},
      {[](v1::NoiseRadiusField& n) { n.set_r_max(0.5); }, "r_max"},  // below r_min
      {[](v1::NoiseRadiusField& n) { n.set_r_max(std::numeric_limits<double>::infinity()); },
       "r_max"},
      {[](v1::NoiseRadiusField& n) { n.set_r_max(101.0); }, "r_max"},  // ratio beyond 100
      {[](v1::NoiseRadiusField& n) { n.set_frequency(0.0); }, "frequency"},
      {[](v1::NoiseRadiusField& n) { n.set_frequency(-0.01); }, "frequency"},
      {[](v1::NoiseRadiusField& n) { n.set_frequency(std::numeric_limits<double>::quiet_NaN()); },
       "frequency"},
      // The slope bound: 3 * 0.2 * 2.65 * (octave factor > 1) is far beyond 1/2.
      {[](v1::NoiseRadiusField& n) { n.set_frequency(0.2); }, "frequency"},
      {[](v1::NoiseRadiusField& n) { n.set_octaves(9); }, "octaves"},
      {[](v1::NoiseRadiusField& n) { n.set_octaves(-1); }, "octaves"},
      {[](v1::NoiseRadiusField& n) { n.set_gain(1.5); }, "gain"},
      {[](v1::NoiseRadiusField& n) { n.set_gain(-0.5); }, "gain"},
  };
  for (const Case& c : cases) {
    v1::RadiusField message = ValidNoise();
    c.plant(*message.mutable_noise());
    ExpectRefused(message, Catalog(), std::string("world.radius_field.noise.") + c.field);
  }
}

TEST(FieldMessagesTest, BadRasterFieldsAreNamed) {
  struct Case {
    void (*plant)(v1::RasterRadiusField&);
    const char* field;
  };
  const Case cases[] = {
      {[](v1::RasterRadiusField& r) { r.set_raster_name(""); }, "raster_name"},
      {[](v1::RasterRadiusField& r) { r.set_raster_name("valleys"); }, "raster_name"},
      {[](v1::RasterRadiusField& r) { r.set_pixel_hash(12345); }, "pixel_hash"},
      {[](v1::RasterRadiusField& r) { r.set_r_min(0.0); }, "r_min"},
      {[](v1::RasterRadiusField& r) { r.set_r_min(std::numeric_limits<double>::quiet_NaN()); },
       "r_min"},
      {[](v1::RasterRadiusField& r) { r.set_r_max(0.9); }, "r_max"},
      {[](v1::RasterRadiusField& r) { r.set_r_max(100.5); }, "r_max"},
      {[](v1::RasterRadiusField& r) { r.set_pixel_size(0.0); }, "pixel_size"},
      {[](v1::RasterRadiusField& r) { r.set_pixel_size(std::numeric_limits<double>::infinity()); },
       "pixel_size"},
      // Steps of 10 levels are 10/254 of the range: at 0.01 a pixel the slope is about 5.6.
      {[](v1::RasterRadiusField& r) { r.set_pixel_size(0.01); }, "pixel_size"},
      {[](v1::RasterRadiusField& r) { r.set_origin_x(std::numeric_limits<double>::quiet_NaN()); },
       "origin_x/origin_y"},
      {[](v1::RasterRadiusField& r) { r.set_origin_y(std::numeric_limits<double>::infinity()); },
       "origin_x/origin_y"},
  };
  for (const Case& c : cases) {
    v1::RadiusField message = ValidRaster();
    c.plant(*message.mutable_raster());
    ExpectRefused(message, Catalog(), std::string("world.radius_field.raster.") + c.field);
  }
}

TEST(FieldMessagesTest, ErrorsNameTheFieldUnderTheCallersPrefix) {
  v1::RadiusField message = ValidNoise();
  message.mutable_noise()->set_frequency(0.2);
  const StatusOr<RadiusFieldSpec> spec =
      RadiusFieldFromMessage(message, Catalog(), "worlds.dunes.radius_field");
  ASSERT_FALSE(spec.ok());
  EXPECT_EQ(spec.status().message().rfind("worlds.dunes.radius_field.noise.frequency: ", 0), 0u)
      << spec.status().message();
  // Every core name is renamed, none left behind.
  EXPECT_EQ(spec.status().message().find(" field."), std::string::npos) << spec.status().message();
}

TEST(FieldMessagesTest, ProseIsNotRenamed) {
  v1::RadiusField message = ValidRaster();
  message.mutable_raster()->set_pixel_size(0.01);
  const StatusOr<RadiusFieldSpec> spec = RadiusFieldFromMessage(message, Catalog());
  ASSERT_FALSE(spec.ok());
  EXPECT_NE(spec.status().message().find("the raster field's slope bound"), std::string::npos)
      << spec.status().message();
}

TEST(FieldMessagesTest, UnknownRasterListsTheLoadedOnesWithoutEchoingTheName) {
  v1::RadiusField message = ValidRaster();
  message.mutable_raster()->set_raster_name("\x1b[31mforged");
  const StatusOr<RadiusFieldSpec> spec = RadiusFieldFromMessage(message, Catalog());
  ASSERT_FALSE(spec.ok());
  EXPECT_NE(spec.status().message().find("loaded: hills"), std::string::npos);
  EXPECT_EQ(spec.status().message().find("forged"), std::string::npos);
}

TEST(RasterCatalogTest, PixelHashSeesEveryPixelTheSizeAndTheDepth) {
  const RasterImage image = GentleImage();
  const uint64_t hash = RasterPixelHash(image);
  EXPECT_EQ(hash, RasterPixelHash(GentleImage()));
  for (size_t k = 0; k < image.pixels.size(); ++k) {
    RasterImage changed = image;
    changed.pixels[k] += 1;
    EXPECT_NE(RasterPixelHash(changed), hash) << k;
  }
  RasterImage deeper = image;
  deeper.bit_depth = 16;
  EXPECT_NE(RasterPixelHash(deeper), hash);
  RasterImage transposed = image;  // the same pixels as 3 x 4
  transposed.width = 3;
  transposed.height = 4;
  EXPECT_NE(RasterPixelHash(transposed), hash);
}

TEST(RasterCatalogTest, NamesAreUniqueAndFilesAreCheckedNamingTheKey) {
  RasterCatalog catalog;
  ASSERT_TRUE(catalog.Add("a", GentleImage()).ok());
  const Status twice = catalog.Add("a", GentleImage(), "rasters.a");
  EXPECT_EQ(twice.code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(twice.message().rfind("rasters.a: ", 0), 0u) << twice.message();
  EXPECT_FALSE(catalog.Add("", GentleImage()).ok());
  EXPECT_EQ(catalog.Names(), "a");
  EXPECT_EQ(RasterCatalog().Names(), "none");

  const std::string missing = testing::TempDir() + "/field_messages_test_missing.png";
  const Status not_there = catalog.Load("b", missing, "rasters.b");
  EXPECT_EQ(not_there.code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(not_there.message().rfind("rasters.b: raster.path: ", 0), 0u) << not_there.message();

  const std::string colour = testing::TempDir() + "/field_messages_test_rgb.png";
  test_png::WritePng(colour, 2, 2, 8, PNG_COLOR_TYPE_RGB, std::vector<uint8_t>(12, 7));
  const Status not_grey = catalog.Load("c", colour, "rasters.c");
  EXPECT_EQ(not_grey.code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(not_grey.message().rfind("rasters.c: raster: ", 0), 0u) << not_grey.message();

  const std::string grey = testing::TempDir() + "/field_messages_test_grey.png";
  test_png::WritePng(grey, 2, 1, 8, PNG_COLOR_TYPE_GRAY, {3, 200});
  ASSERT_TRUE(catalog.Load("d", grey, "rasters.d").ok());
  const NamedRaster* d = catalog.Find("d");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->image->pixels, (std::vector<uint16_t>{3, 200}));
  EXPECT_EQ(catalog.FindImage(d->image.get()), d);
  EXPECT_EQ(catalog.FindImage(nullptr), nullptr);
  EXPECT_EQ(catalog.Names(), "a, d");
}

}  // namespace
}  // namespace scallop
