// Writes PNG files for tests with libpng's classic API (any bit depth and colour type, so tests
// can make the files the raster loader must refuse as well as those it reads).
#pragma once

#include <gtest/gtest.h>
#include <png.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace scallop::test_png {

// Rows are given top row first, as the file stores them; `bytes` holds them packed as libpng
// writes them (16-bit samples big-endian).
inline void WritePng(const std::string& path, int width, int height, int bit_depth, int color_type,
                     const std::vector<uint8_t>& bytes) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  ASSERT_NE(f, nullptr) << path;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  png_init_io(png, f);
  png_set_IHDR(png, info, width, height, bit_depth, color_type, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  const int channels = color_type == PNG_COLOR_TYPE_RGB ? 3 : 1;
  const size_t row = (static_cast<size_t>(width) * channels * bit_depth + 7) / 8;
  for (int r = 0; r < height; ++r) png_write_row(png, bytes.data() + r * row);
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  std::fclose(f);
}

}  // namespace scallop::test_png
