// LoadGrayscalePng on hostile files: what fuzz/raster_png_fuzzer found, pinned.
#include "scallop/field/raster_png.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace scallop {
namespace {

int64_t PeakResidentKilobytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss;
}

// An 80-byte PNG (a 3 x 1 grey image) whose zTXt chunk declares 1.4 GB
// (length bytes "THDR" = 0x54484452). libpng allocated and zeroed the whole
// declared length before reading it: 1.6 GB of memory and 6 s for 80 bytes.
TEST(RasterPng, ChunkDeclaringGigabytesAllocatesNothingLarge) {
  const std::vector<uint8_t> file = {
      0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48,
      0x44, 0x52, 0x00, 0x00, 0x00, 0x03, 0x00, 0x00, 0x00, 0x01, 0x01, 0x00, 0x00, 0x00,
      0x00, 0x33, 0x9b, 0x29, 0x19, 0x00, 0x00, 0x00, 0x0d, 0x67, 0x41, 0x4d, 0x41, 0x39,
      0x00, 0x49, 0x44, 0x41, 0x54, 0x4e, 0x47, 0x0d, 0x3f, 0x0a, 0x2a, 0x0a, 0x49, 0x49,
      0x44, 0x41, 0x54, 0x48, 0x44, 0x52, 0x7a, 0x54, 0x58, 0x74, 0x44, 0x01, 0x01, 0x89};
  const std::string path =
      testing::TempDir() + "raster_png_test_" + std::to_string(getpid()) + "_huge_chunk.png";
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(file.data()), static_cast<std::streamsize>(file.size()));

  const int64_t before = PeakResidentKilobytes();
  const StatusOr<RasterImage> image = LoadGrayscalePng(path);
  const int64_t grown_megabytes = (PeakResidentKilobytes() - before) / 1024;
  std::remove(path.c_str());

  ASSERT_FALSE(image.ok());
  EXPECT_TRUE(image.status().message().starts_with("raster")) << image.status().message();
  // The chunk cap is 1 MiB; 64 MB leaves room for the allocator and still
  // catches the gigabyte.
  EXPECT_LT(grown_megabytes, 64) << "peak resident memory grew by " << grown_megabytes << " MB";
}

}  // namespace
}  // namespace scallop
