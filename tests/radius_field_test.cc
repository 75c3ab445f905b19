// RadiusField: raster evaluation against hand-computed values (bilinear between pixel centres,
// edges held beyond the image, masks), noise determinism, range and slope, interval bounds,
// validation messages naming the field, the PNG loader and the fingerprint.
#include "scallop/field/radius_field.h"

#include <gtest/gtest.h>
#include <png.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "scallop/field/raster_png.h"
#include "scallop/random/rng.h"
#include "tests/field_test_fields.h"
#include "tests/test_png.h"

namespace scallop {
namespace {

// 3 x 2, rows bottom-up: bottom 1, 255, 128; top 0 (masked), 64, 1. r in [1, 5]:
// R(v) = 1 + 4 (v - 1) / 254, so R(1) = 1, R(255) = 5, R(128) = 3, R(64) = 1 + 252/254, and the
// masked pixel counts as 5. Largest step 4 both ways: L = sqrt(32) / 12 = 0.471.
RadiusFieldSpec SmallRasterSpec() {
  auto image = std::make_shared<RasterImage>();
  image->width = 3;
  image->height = 2;
  image->bit_depth = 8;
  image->pixels = {1, 255, 128, 0, 64, 1};
  RadiusFieldSpec spec;
  spec.kind = RadiusFieldKind::kRaster;
  spec.r_min = 1.0;
  spec.r_max = 5.0;
  spec.raster = image;
  spec.raster_origin = {100.0, 200.0};
  spec.pixel_size = 12.0;
  return spec;
}

constexpr double kR64 = 1.0 + 252.0 / 254.0;

TEST(RadiusFieldTest, RasterIsBilinearBetweenPixelCentres) {
  const RadiusField field = *RadiusField::Create(SmallRasterSpec());
  // Centres (origin + 12 (i + 1/2), 200 + 12 (j + 1/2)).
  EXPECT_DOUBLE_EQ(field.Evaluate({106, 206}), 1.0);
  EXPECT_DOUBLE_EQ(field.Evaluate({118, 206}), 5.0);
  EXPECT_DOUBLE_EQ(field.Evaluate({130, 206}), 3.0);
  EXPECT_DOUBLE_EQ(field.Evaluate({106, 218}), 5.0);  // masked counts as v_max
  EXPECT_DOUBLE_EQ(field.Evaluate({118, 218}), kR64);
  EXPECT_DOUBLE_EQ(field.Evaluate({130, 218}), 1.0);
  // Between centres.
  EXPECT_DOUBLE_EQ(field.Evaluate({112, 206}), 3.0);
  EXPECT_NEAR(field.Evaluate({112, 212}), (1.0 + 5.0 + 5.0 + kR64) / 4.0, 1e-14);
  EXPECT_NEAR(field.Evaluate({109, 209}),
              0.75 * 0.75 * 1.0 + 0.25 * 0.75 * 5.0 + 0.75 * 0.25 * 5.0 + 0.25 * 0.25 * kR64,
              1e-14);
  // Beyond the image the edge pixels' values hold.
  EXPECT_DOUBLE_EQ(field.Evaluate({50, 150}), 1.0);
  EXPECT_DOUBLE_EQ(field.Evaluate({200, 206}), 3.0);
  EXPECT_DOUBLE_EQ(field.Evaluate({112, 150}), 3.0);
  EXPECT_NEAR(field.Evaluate({112, 300}), (5.0 + kR64) / 2.0, 1e-14);
  EXPECT_DOUBLE_EQ(field.Evaluate({1e300, -1e300}), 3.0);
  const double odd = field.Evaluate({NAN, INFINITY});
  EXPECT_TRUE(odd >= 1.0 && odd <= 5.0);
  const RadiusField noise = field_test::NoiseField(1, 1.0, 4.0);
  for (const Vec2 x : {Vec2{NAN, 0.0}, Vec2{INFINITY, -INFINITY}, Vec2{1e300, 1e-300}}) {
    const double r = noise.Evaluate(x);
    EXPECT_TRUE(r >= 1.0 && r <= 4.0) << r;
  }
  EXPECT_NEAR(field.Slope(), std::sqrt(32.0) / 12.0, 1e-9);
}

TEST(RadiusFieldTest, MaskIsThePixelSquareOfAZeroPixel) {
  const RadiusField field = *RadiusField::Create(SmallRasterSpec());
  ASSERT_TRUE(field.HasMask());
  // Pixel (0, 1): [100, 112) x [212, 224), the bottom row is the lowest y.
  EXPECT_TRUE(field.IsMasked({100, 212}));
  EXPECT_TRUE(field.IsMasked({111.9, 223.9}));
  EXPECT_FALSE(field.IsMasked({112, 213}));
  EXPECT_FALSE(field.IsMasked({101, 211.9}));
  EXPECT_FALSE(field.IsMasked({99.9, 213}));
  EXPECT_FALSE(field.IsMasked({101, 224}));
  EXPECT_TRUE(field.AllMasked({101, 213, 111, 223}));
  EXPECT_TRUE(field.AllMasked({100, 212, 112, 224}));  // its edges belong to neighbours
  EXPECT_FALSE(field.AllMasked({101, 213, 113, 223}));
  EXPECT_TRUE(field.AnyMasked({90, 190, 101, 213}));
  EXPECT_FALSE(field.AnyMasked({112, 200, 136, 224}));
  Rect pieces[4];
  ASSERT_EQ(field.CutAtPixelLines({105, 205, 119, 219}, pieces), 4);
  EXPECT_EQ(pieces[0], (Rect{105, 205, 112, 212}));
  EXPECT_EQ(pieces[3], (Rect{112, 212, 119, 219}));
}

TEST(RadiusFieldTest, NoiseIsDeterministicInRangeAndWithinItsSlope) {
  const RadiusField a = field_test::NoiseField(42, 0.5, 16.0);
  const RadiusField b = field_test::NoiseField(42, 0.5, 16.0);
  const RadiusField c = field_test::NoiseField(43, 0.5, 16.0);
  Rng rng(7);
  uint64_t hash = 0;
  int differ = 0;
  double worst_slope = 0.0;
  for (int k = 0; k < 20000; ++k) {
    const Vec2 x{rng.Uniform(-1e5, 1e5), rng.Uniform(-1e5, 1e5)};
    const double r = a.Evaluate(x);
    ASSERT_EQ(std::bit_cast<uint64_t>(r), std::bit_cast<uint64_t>(b.Evaluate(x)));
    ASSERT_GE(r, a.r_min());
    ASSERT_LE(r, a.r_max());
    differ += r != c.Evaluate(x) ? 1 : 0;
    hash = Mix64(hash + std::bit_cast<uint64_t>(r));
    const Vec2 y{x.x + rng.Uniform(-1.0, 1.0), x.y + rng.Uniform(-1.0, 1.0)};
    const double d = std::hypot(y.x - x.x, y.y - x.y);
    if (d > 0.0) worst_slope = std::max(worst_slope, std::abs(a.Evaluate(y) - r) / d);
  }
  EXPECT_GT(differ, 19000);
  EXPECT_LE(worst_slope, a.Slope());
  std::printf("noise slope: measured %.4f, bound %.4f; value hash %016llx\n", worst_slope,
              a.Slope(), static_cast<unsigned long long>(hash));
  // Pinned: a change here changes every noise world's points.
  EXPECT_EQ(hash, 0x70328e68984c2d08ULL);
}

TEST(RadiusFieldTest, BoundsHoldEverySpotOfTheRectangle) {
  const RadiusField fields[] = {field_test::NoiseField(3, 1.0, 8.0),
                                *RadiusField::Create(SmallRasterSpec())};
  Rng rng(11);
  for (const RadiusField& field : fields) {
    for (int k = 0; k < 2000; ++k) {
      const double x0 = rng.Uniform(80.0, 150.0);
      const double y0 = rng.Uniform(180.0, 240.0);
      const double side = rng.Uniform(0.01, 20.0);
      const Rect r{x0, y0, x0 + side, y0 + side * rng.Uniform(0.2, 2.0)};
      const RadiusInterval bounds = field.Bounds(r);
      for (int m = 0; m < 20; ++m) {
        const Vec2 p{rng.Uniform(r.x0, r.x1), rng.Uniform(r.y0, r.y1)};
        const double v = field.Evaluate(p);
        ASSERT_LE(bounds.lo, v);
        ASSERT_GE(bounds.hi, v);
      }
    }
  }
}

// The message of the first problem ValidateRadiusFieldSpec finds.
std::string Problem(const RadiusFieldSpec& spec) {
  const Status s = ValidateRadiusFieldSpec(spec);
  EXPECT_FALSE(s.ok());
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_FALSE(RadiusField::Create(spec).ok());
  return s.message();
}

TEST(RadiusFieldTest, ValidationNamesTheField) {
  RadiusFieldSpec noise;
  noise.kind = RadiusFieldKind::kNoise;
  noise.r_min = 1.0;
  noise.r_max = 4.0;
  noise.frequency = 0.01;
  ASSERT_TRUE(ValidateRadiusFieldSpec(noise).ok());
  auto with = [&](auto change) {
    RadiusFieldSpec s = noise;
    change(s);
    return Problem(s);
  };
  EXPECT_NE(with([](auto& s) { s.r_min = 0.0; }).find("field.r_min"), std::string::npos);
  EXPECT_NE(with([](auto& s) { s.r_min = -1.0; }).find("field.r_min"), std::string::npos);
  EXPECT_NE(with([](auto& s) { s.r_min = NAN; }).find("field.r_min"), std::string::npos);
  EXPECT_NE(with([](auto& s) { s.r_max = NAN; }).find("field.r_max"), std::string::npos);
  EXPECT_NE(with([](auto& s) { s.r_max = 0.5; }).find("field.r_max"), std::string::npos);
  EXPECT_NE(with([](auto& s) { s.r_max = 101.0; }).find("field.r_max / field.r_min"),
            std::string::npos);
  EXPECT_NE(with([](auto& s) { s.frequency = 0.0; }).find("field.frequency"), std::string::npos);
  EXPECT_NE(with([](auto& s) { s.frequency = 1.0; }).find("slope"), std::string::npos);
  EXPECT_NE(with([](auto& s) { s.frequency = 1.0; }).find("field.frequency"), std::string::npos);
  EXPECT_NE(with([](auto& s) { s.octaves = 0; }).find("field.octaves"), std::string::npos);
  EXPECT_NE(with([](auto& s) { s.octaves = 9; }).find("field.octaves"), std::string::npos);
  EXPECT_NE(with([](auto& s) { s.gain = 1.5; }).find("field.gain"), std::string::npos);

  RadiusFieldSpec constant;
  constant.r_min = 1.0;
  constant.r_max = 2.0;
  EXPECT_NE(Problem(constant).find("field.r_max"), std::string::npos);

  const RadiusFieldSpec raster = SmallRasterSpec();
  ASSERT_TRUE(ValidateRadiusFieldSpec(raster).ok());
  auto raster_with = [&](auto change) {
    RadiusFieldSpec s = raster;
    auto image = std::make_shared<RasterImage>(*raster.raster);
    change(s, *image);
    if (s.raster != nullptr) s.raster = image;
    return Problem(s);
  };
  EXPECT_NE(raster_with([](auto& s, auto&) { s.raster = nullptr; }).find("raster is missing"),
            std::string::npos);
  EXPECT_NE(raster_with([](auto&, auto& i) { i.bit_depth = 12; }).find("raster.bit_depth"),
            std::string::npos);
  EXPECT_NE(raster_with([](auto&, auto& i) {
              i.width = 20000;
              i.height = 1;
            }).find("16384"),
            std::string::npos);
  EXPECT_NE(raster_with([](auto&, auto& i) { i.pixels.pop_back(); }).find("raster.pixels"),
            std::string::npos);
  EXPECT_NE(raster_with([](auto&, auto& i) { i.pixels[1] = 300; }).find("raster.pixels"),
            std::string::npos);
  EXPECT_NE(raster_with([](auto& s, auto&) { s.pixel_size = 0.0; }).find("raster.pixel_size"),
            std::string::npos);
  // A step of 4 over a pixel of 11: slope 0.51 > 0.5.
  const std::string steep = raster_with([](auto& s, auto&) { s.pixel_size = 11.0; });
  EXPECT_NE(steep.find("raster.pixel_size"), std::string::npos);
  EXPECT_NE(steep.find("slope"), std::string::npos);
  EXPECT_NE(raster_with([](auto& s, auto&) { s.raster_origin.x = INFINITY; }).find("raster.origin"),
            std::string::npos);
}

TEST(RadiusFieldTest, FingerprintFollowsEveryParameterAndPixel) {
  const RadiusField a = *RadiusField::Create(SmallRasterSpec());
  EXPECT_EQ(a.Fingerprint(), RadiusField::Create(SmallRasterSpec())->Fingerprint());
  RadiusFieldSpec changed = SmallRasterSpec();
  auto image = std::make_shared<RasterImage>(*changed.raster);
  image->pixels[4] = 65;
  changed.raster = image;
  EXPECT_NE(a.Fingerprint(), RadiusField::Create(changed)->Fingerprint());
  RadiusFieldSpec moved = SmallRasterSpec();
  moved.raster_origin.x += 1.0;
  EXPECT_NE(a.Fingerprint(), RadiusField::Create(moved)->Fingerprint());
  EXPECT_NE(field_test::NoiseField(1, 1.0, 4.0).Fingerprint(),
            field_test::NoiseField(2, 1.0, 4.0).Fingerprint());
  EXPECT_NE(RadiusField::Constant(1.0).Fingerprint(), RadiusField::Constant(2.0).Fingerprint());
}

using test_png::WritePng;

std::string TempPath(const char* name) {
  return testing::TempDir() + "/radius_field_test_" + name + ".png";
}

TEST(RadiusFieldTest, PngLoaderReadsGrayBottomRowFirst) {
  const std::string path8 = TempPath("gray8");
  WritePng(path8, 3, 2, 8, PNG_COLOR_TYPE_GRAY, {0, 64, 1, 1, 255, 128});
  const StatusOr<RasterImage> image8 = LoadGrayscalePng(path8);
  ASSERT_TRUE(image8.ok()) << image8.status().message();
  EXPECT_EQ(image8->bit_depth, 8);
  EXPECT_EQ(image8->pixels, (std::vector<uint16_t>{1, 255, 128, 0, 64, 1}));

  const std::string path16 = TempPath("gray16");
  WritePng(path16, 2, 1, 16, PNG_COLOR_TYPE_GRAY, {0x01, 0x02, 0xff, 0xfe});
  const StatusOr<RasterImage> image16 = LoadGrayscalePng(path16);
  ASSERT_TRUE(image16.ok()) << image16.status().message();
  EXPECT_EQ(image16->bit_depth, 16);
  EXPECT_EQ(image16->pixels, (std::vector<uint16_t>{0x0102, 0xfffe}));
}

TEST(RadiusFieldTest, PngLoaderRejectsWhatItCannotUse) {
  const StatusOr<RasterImage> missing = LoadGrayscalePng(TempPath("does_not_exist"));
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.status().message().find("raster.path"), std::string::npos);

  const std::string rgb = TempPath("rgb");
  WritePng(rgb, 2, 2, 8, PNG_COLOR_TYPE_RGB, std::vector<uint8_t>(12, 7));
  const StatusOr<RasterImage> colour = LoadGrayscalePng(rgb);
  ASSERT_FALSE(colour.ok());
  EXPECT_NE(colour.status().message().find("grayscale"), std::string::npos);

  const std::string low = TempPath("gray4");
  WritePng(low, 2, 2, 4, PNG_COLOR_TYPE_GRAY, {0x12, 0x34});
  const StatusOr<RasterImage> four_bit = LoadGrayscalePng(low);
  ASSERT_FALSE(four_bit.ok());
  EXPECT_NE(four_bit.status().message().find("bit depth 4"), std::string::npos);

  const std::string wide = TempPath("wide");
  WritePng(wide, 20000, 1, 8, PNG_COLOR_TYPE_GRAY, std::vector<uint8_t>(20000, 9));
  const StatusOr<RasterImage> too_large = LoadGrayscalePng(wide);
  ASSERT_FALSE(too_large.ok());
  EXPECT_NE(too_large.status().message().find("16384"), std::string::npos);

  const std::string text = testing::TempDir() + "/radius_field_test_not_png.png";
  std::FILE* f = std::fopen(text.c_str(), "wb");
  std::fputs("not a png at all", f);
  std::fclose(f);
  const StatusOr<RasterImage> not_png = LoadGrayscalePng(text);
  ASSERT_FALSE(not_png.ok());
  EXPECT_NE(not_png.status().message().find("not a PNG"), std::string::npos);

  // A truncated file: the header is fine, the pixels are cut off.
  const std::string whole = TempPath("whole");
  WritePng(whole, 64, 64, 8, PNG_COLOR_TYPE_GRAY, std::vector<uint8_t>(64 * 64, 200));
  std::FILE* in = std::fopen(whole.c_str(), "rb");
  std::vector<char> bytes(4096);
  const size_t n = std::fread(bytes.data(), 1, bytes.size(), in);
  std::fclose(in);
  const std::string cut = TempPath("cut");
  std::FILE* out = std::fopen(cut.c_str(), "wb");
  std::fwrite(bytes.data(), 1, n > 60 ? 60 : n, out);
  std::fclose(out);
  EXPECT_FALSE(LoadGrayscalePng(cut).ok());
}

}  // namespace
}  // namespace scallop
