// What a tile URL names: a world, a tile (a square block of 2^level x 2^level
// regions) and a format, parsed from GET /v1/worlds/{world}/tiles/{i}/{j}
// with checks that name the bad part. No I/O; the handler is http_tiles.h.
// The layout is documented in docs/tiles.md.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "scallop/base/status.h"
#include "scallop/geometry/rect.h"
#include "scallop/plane/region_layout.h"

namespace scallop::server {

// Levels a tile may have. A level-L tile is 16 * 2^L d on a side; the area
// limit (max_query_area) decides which of these a server serves (level 5,
// 512 d, is the largest under the default 1e6 d^2).
inline constexpr int kMaxTileLevel = 20;

// Tile (level, i, j) covers regions [i 2^level, (i+1) 2^level) x [j 2^level,
// (j+1) 2^level): at level 0 it is region (i, j) itself.
struct TileKey {
  int level = 0;
  int64_t i = 0;
  int64_t j = 0;
};

enum class TileFormat { kJson, kBinary, kPng };

// "json", "bin", "png": the extension and the format= value.
std::string_view TileFormatName(TileFormat format);
// application/json, application/vnd.scallop.tile, image/png.
std::string_view TileContentType(TileFormat format);

struct TileAddress {
  std::string world;  // percent-decoded world name
  TileKey key;
  TileFormat format = TileFormat::kJson;
  // The URL chose the format (extension or format=); else the Accept header
  // did, and the answer must say "Vary: Accept".
  bool format_in_url = false;
};

// True when `target` (path and query) starts with /v1/worlds/ and has a
// /tiles/ segment: what ParseTileAddress is for.
bool IsTileTarget(std::string_view target);

// Parses /v1/worlds/{world}/tiles/{i}/{j}[.json|.bin|.png] and the query
// parameters level (0..kMaxTileLevel, default 0) and format (json, bin,
// png), which must agree with an extension when both are given; `accept`
// (the Accept header, may be empty) picks the format when the URL does not.
// INVALID_ARGUMENT naming the part: a malformed path, i or j not a decimal
// integer (no sign but '-', no leading zeros, no spaces, points or
// exponents), an unknown or repeated parameter, a bad level or format.
// OUT_OF_RANGE when i or j does not fit 64 bits or puts the tile beyond the
// precision range (|coordinate| <= 2^32 d), naming the allowed range.
StatusOr<TileAddress> ParseTileAddress(std::string_view target, std::string_view accept);

// The half-open rectangle of `key`: the union of its regions, with edges
// that are the regions' own edges bit for bit. REQUIRES: key as
// ParseTileAddress returns it (level and indices in range).
Rect TileRect(const RegionLayout& layout, const TileKey& key);

}  // namespace scallop::server
