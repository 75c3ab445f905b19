// LoadGrayscalePng with libpng's classic API: the simplified API would apply gamma to 16-bit
// data, and a raster's values must reach the field exactly as stored.
#include "scallop/field/raster_png.h"

#include <png.h>

#include <cstdio>
#include <memory>
#include <vector>

namespace scallop {
namespace {

// Every ancillary chunk libpng knows, 4 letters and a NUL each. A raster is its samples alone,
// and libpng allocates (and zeroes) such a chunk's declared length before reading it: an 80-byte
// file declaring a 1.4 GB zTXt chunk took 1.4 GB and 6 s (found by fuzz/raster_png_fuzzer;
// png_set_chunk_malloc_max does not bound it in libpng 1.6.39). Skipped unread instead.
constexpr png_byte kAncillaryChunks[] =
    "bKGD\0cHRM\0eXIf\0gAMA\0hIST\0iCCP\0iTXt\0oFFs\0pCAL\0pHYs\0sBIT\0sCAL\0sPLT\0sRGB\0tEXt\0"
    "tIME\0tRNS\0zTXt";
constexpr int kAncillaryChunkCount = sizeof kAncillaryChunks / 5;

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

// libpng reports errors by longjmp; nothing with a destructor may live between setjmp and the
// calls that can jump, so the decoding runs in this function with plain pointers only, into
// memory the caller owns.
bool DecodeRows(png_structp png, png_infop info, png_bytep* rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_image(png, rows);
  png_read_end(png, info);
  return true;
}

bool ReadHeader(png_structp png, png_infop info, std::FILE* file, png_uint_32* width,
                png_uint_32* height, int* bit_depth, int* color_type) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_init_io(png, file);
  png_set_user_limits(png, kMaxRasterSide, kMaxRasterSide);
  png_set_keep_unknown_chunks(png, PNG_HANDLE_CHUNK_NEVER, nullptr, 0);  // unknown ones too
  png_set_keep_unknown_chunks(png, PNG_HANDLE_CHUNK_NEVER, kAncillaryChunks, kAncillaryChunkCount);
  png_read_info(png, info);
  int interlace = 0;
  png_get_IHDR(png, info, width, height, bit_depth, color_type, &interlace, nullptr, nullptr);
  if (interlace != PNG_INTERLACE_NONE) png_set_interlace_handling(png);
  png_read_update_info(png, info);
  return true;
}

}  // namespace

StatusOr<RasterImage> LoadGrayscalePng(const std::string& path) {
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file) return InvalidArgument("raster.path: cannot open '" + path + "'");
  png_byte signature[8];
  if (std::fread(signature, 1, 8, file.get()) != 8 || png_sig_cmp(signature, 0, 8) != 0) {
    return InvalidArgument("raster.path: '" + path + "' is not a PNG file");
  }
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  if (png == nullptr) return InvalidArgument("raster.path: libpng could not start");
  png_infop info = png_create_info_struct(png);
  struct Guard {
    png_structp* png;
    png_infop* info;
    ~Guard() { png_destroy_read_struct(png, info, nullptr); }
  } guard{&png, &info};
  if (info == nullptr) return InvalidArgument("raster.path: libpng could not start");
  png_set_sig_bytes(png, 8);
  // Silence libpng's own warnings on stderr; errors still longjmp into the checks below.
  png_set_error_fn(
      png, nullptr, [](png_structp p, png_const_charp) { png_longjmp(p, 1); },
      [](png_structp, png_const_charp) {});
  png_uint_32 width = 0;
  png_uint_32 height = 0;
  int bit_depth = 0;
  int color_type = 0;
  if (!ReadHeader(png, info, file.get(), &width, &height, &bit_depth, &color_type)) {
    return InvalidArgument("raster.path: '" + path +
                           "' has a corrupt header or a side above 16384 pixels");
  }
  if (color_type != PNG_COLOR_TYPE_GRAY) {
    return InvalidArgument("raster: '" + path +
                           "' is not a plain grayscale PNG (colour, palette or alpha); "
                           "convert it to 8- or 16-bit gray");
  }
  if (bit_depth != 8 && bit_depth != 16) {
    return InvalidArgument("raster: '" + path + "' has bit depth " + std::to_string(bit_depth) +
                           ", must be 8 or 16");
  }
  if (width > static_cast<png_uint_32>(kMaxRasterSide) ||
      height > static_cast<png_uint_32>(kMaxRasterSide) ||
      int64_t{width} * height > kMaxRasterPixels) {
    return InvalidArgument("raster: '" + path + "' is " + std::to_string(width) + " x " +
                           std::to_string(height) +
                           " pixels; at most 16384 a side and 2^24 pixels in all");
  }
  const size_t row_bytes = static_cast<size_t>(width) * (bit_depth / 8);
  std::vector<png_byte> bytes(row_bytes * height);
  std::vector<png_bytep> rows(height);
  for (png_uint_32 r = 0; r < height; ++r) rows[r] = bytes.data() + r * row_bytes;
  if (!DecodeRows(png, info, rows.data())) {
    return InvalidArgument("raster.path: '" + path + "' is corrupt (decoding failed)");
  }
  RasterImage image;
  image.width = static_cast<int>(width);
  image.height = static_cast<int>(height);
  image.bit_depth = bit_depth;
  image.pixels.resize(static_cast<size_t>(width) * height);
  for (png_uint_32 r = 0; r < height; ++r) {
    const png_byte* src = rows[r];
    uint16_t* dst = image.pixels.data() + static_cast<size_t>(height - 1 - r) * width;
    for (png_uint_32 i = 0; i < width; ++i) {
      dst[i] = bit_depth == 16 ? static_cast<uint16_t>((src[2 * i] << 8) | src[2 * i + 1])
                               : src[i];  // PNG stores 16-bit samples big-endian
    }
  }
  return image;
}

}  // namespace scallop
