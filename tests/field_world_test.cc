// A World with a radius field (issue 24): validation with errors in the world's namespace, the
// a3-only rule, a constant field normalised to the plain world (same fingerprint, hence same
// points), the fingerprint covering the field (a raster by its pixels, not its address), and
// the spacing accessors.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "scallop/plane/world.h"
#include "tests/field_test_fields.h"
#include "tests/test_worlds.h"

namespace scallop {
namespace {

RadiusFieldSpec NoiseSpec() {
  RadiusFieldSpec spec;
  spec.kind = RadiusFieldKind::kNoise;
  spec.r_min = 0.5;
  spec.r_max = 4.0;
  spec.noise_seed = 11;
  spec.frequency = 0.01;
  spec.octaves = 2;
  return spec;
}

// A 4 x 3 raster, gently sloped, with one masked pixel.
RadiusFieldSpec RasterSpec() {
  auto image = std::make_shared<RasterImage>();
  image->width = 4;
  image->height = 3;
  image->bit_depth = 8;
  image->pixels = {1, 40, 80, 120, 40, 0, 120, 160, 80, 120, 160, 200};
  RadiusFieldSpec spec;
  spec.kind = RadiusFieldKind::kRaster;
  spec.r_min = 1.0;
  spec.r_max = 3.0;
  spec.raster = image;
  spec.raster_origin = {-20.0, 10.0};
  spec.pixel_size = 10.0;
  return spec;
}

WorldSpec FieldWorldSpec(const RadiusFieldSpec& field, uint64_t seed = 7) {
  WorldSpec spec{.seed = seed, .min_distance = 123.0, .algorithm = WorldAlgorithm::kA3};
  spec.radius_field = field;
  return spec;
}

void ExpectInvalid(const WorldSpec& spec, const std::string& field, const std::string& what) {
  StatusOr<World> world = World::Create(spec);
  ASSERT_FALSE(world.ok()) << what;
  EXPECT_EQ(world.status().code(), StatusCode::kInvalidArgument) << what;
  EXPECT_TRUE(world.status().message().starts_with(field))
      << what << ": '" << world.status().message() << "' should start with " << field;
}

TEST(FieldWorldTest, BadFieldsAreNamedInTheWorldsNamespace) {
  RadiusFieldSpec bad = NoiseSpec();
  bad.r_min = 0.0;
  ExpectInvalid(FieldWorldSpec(bad), "world.radius_field.r_min", "r_min 0");
  bad = NoiseSpec();
  bad.r_max = 1000.0;  // ratio 2000
  ExpectInvalid(FieldWorldSpec(bad), "world.radius_field.r_max", "ratio beyond 100");
  bad = NoiseSpec();
  bad.frequency = 1.0;  // far too steep
  ExpectInvalid(FieldWorldSpec(bad), "world.radius_field.frequency", "slope");
  bad = RasterSpec();
  bad.pixel_size = 0.5;
  ExpectInvalid(FieldWorldSpec(bad), "world.radius_field.raster.pixel_size", "raster slope");
  bad = RasterSpec();
  bad.raster = nullptr;
  ExpectInvalid(FieldWorldSpec(bad), "world.radius_field.raster", "missing raster");
  // Only A3 takes a field; a constant field is the plain world, so any algorithm may.
  WorldSpec a1 = FieldWorldSpec(NoiseSpec());
  a1.algorithm = WorldAlgorithm::kA1;
  a1.density = 1.5;
  ExpectInvalid(a1, "world.algorithm", "a1 with a noise field");
  a1.radius_field = RadiusFieldSpec{.r_min = 2.0, .r_max = 2.0};
  EXPECT_TRUE(World::Create(a1).ok());
}

TEST(FieldWorldTest, ConstantFieldIsThePlainWorld) {
  for (WorldAlgorithm algorithm : {WorldAlgorithm::kA1, WorldAlgorithm::kA3}) {
    WorldSpec plain{.seed = 5, .min_distance = 2.5, .algorithm = algorithm, .density = 1.5};
    WorldSpec with_field = plain;
    with_field.min_distance = 99.0;  // ignored: the field's r wins
    with_field.radius_field = RadiusFieldSpec{.r_min = 2.5, .r_max = 2.5};
    const World a = ValidWorld(plain);
    const World b = ValidWorld(with_field);
    EXPECT_EQ(a, b);
    EXPECT_EQ(a.fingerprint(), b.fingerprint());
    EXPECT_EQ(b.radius_field(), nullptr);
    EXPECT_FALSE(b.spec().radius_field.has_value());
    EXPECT_EQ(b.min_distance(), 2.5);
    EXPECT_EQ(b.SpacingAt({3.0, -4.0}), 2.5);
    EXPECT_EQ(b.max_spacing(), 2.5);
    EXPECT_EQ(a.Describe(), b.Describe());
  }
}

TEST(FieldWorldTest, FieldWorldIsNormalisedAndFingerprinted) {
  const World noise = ValidWorld(FieldWorldSpec(NoiseSpec()));
  ASSERT_NE(noise.radius_field(), nullptr);
  EXPECT_EQ(noise.min_distance(), 0.5);
  EXPECT_EQ(noise.max_spacing(), 4.0);
  const RadiusField reference = *RadiusField::Create(NoiseSpec());
  for (Vec2 x : {Vec2{0, 0}, Vec2{13.5, -7.25}, Vec2{1e6, 3e5}}) {
    EXPECT_EQ(noise.SpacingAt(x), reference.Evaluate(x));
  }
  EXPECT_NE(noise.Describe().find("field=noise r=[0.5,4]"), std::string::npos) << noise.Describe();
  // The plain world at d = r_min is another world.
  const World plain =
      ValidWorld({.seed = 7, .min_distance = 0.5, .algorithm = WorldAlgorithm::kA3});
  EXPECT_NE(noise.fingerprint(), plain.fingerprint());
  EXPECT_FALSE(noise == plain);
  // min_distance given does not matter; every field parameter does.
  WorldSpec other_d = FieldWorldSpec(NoiseSpec());
  other_d.min_distance = 1.0;
  EXPECT_EQ(ValidWorld(other_d), noise);
  EXPECT_EQ(ValidWorld(other_d).fingerprint(), noise.fingerprint());
  RadiusFieldSpec other_seed = NoiseSpec();
  other_seed.noise_seed = 12;
  EXPECT_NE(ValidWorld(FieldWorldSpec(other_seed)).fingerprint(), noise.fingerprint());
  EXPECT_NE(noise.WithSeed(8).fingerprint(), noise.fingerprint());
  EXPECT_NE(noise.WithSeed(8).radius_field(), nullptr);
  EXPECT_EQ(noise.WithSeed(8).WithSeed(7), noise);
}

TEST(FieldWorldTest, RasterWorldsCompareByPixelsNotByImage) {
  const World a = ValidWorld(FieldWorldSpec(RasterSpec()));
  const World b = ValidWorld(FieldWorldSpec(RasterSpec()));  // another copy of the same image
  ASSERT_NE(a.spec().radius_field->raster, b.spec().radius_field->raster);
  EXPECT_EQ(a, b);
  EXPECT_EQ(a.fingerprint(), b.fingerprint());
  EXPECT_NE(a.Describe().find("field=raster r=[1,3] raster=4x3x8"), std::string::npos)
      << a.Describe();
  RadiusFieldSpec changed = RasterSpec();
  auto image = std::make_shared<RasterImage>(*changed.raster);
  image->pixels[0] = 2;
  changed.raster = image;
  const World c = ValidWorld(FieldWorldSpec(changed));
  EXPECT_FALSE(a == c);
  EXPECT_NE(a.fingerprint(), c.fingerprint());
  EXPECT_EQ(a.max_spacing(), 3.0);
  EXPECT_EQ(a.min_distance(), 1.0);
}

}  // namespace
}  // namespace scallop
