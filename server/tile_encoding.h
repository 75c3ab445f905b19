// A tile's points in its three formats: JSON, the compact little-endian
// binary format, and a PNG picture. Pure functions of the tile, so equal
// tiles give equal bytes (what the strong ETags promise). Every format is
// documented byte by byte in docs/tiles.md.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scallop/base/status.h"
#include "scallop/geometry/rect.h"
#include "scallop/plane/world.h"
#include "server/tile_address.h"

namespace scallop::server {

// Bumped whenever any format's bytes change for the same points (a field
// added, the PNG drawn otherwise): it is part of every ETag, so caches never
// mix an old rendering with a new one.
// Version 3: tiles of radius-field worlds carry each point's R (rs) and
// draw their PNG disks at R/4; constant worlds' bytes are version 2's.
inline constexpr int kTileFormatVersion = 3;

// Which world and tile the points are, and the points in query order.
struct Tile {
  std::string world_name;
  World world;
  TileKey key;
  Rect rect;
  std::vector<uint64_t> ids;
  std::vector<double> xs;
  std::vector<double> ys;
  // R(p) at each point of a radius-field world (the spacing the world asks
  // there, as Points.radii carries it); empty for a world without a field.
  std::vector<double> rs;
};

// {"world", "level", "i", "j", "rect", "fingerprint", "generator_version",
// "min_distance", "count", "ids" (decimal strings), "xs", "ys", and for a
// radius-field world "rs"}; numbers are the shortest text that reads back
// to the same double.
std::string EncodeTileJson(const Tile& tile);

// The 80-byte header, then ids (u64), xs and ys (f64), and for a
// radius-field world rs (f64, flag bit 0), all little-endian.
std::string EncodeTileBinary(const Tile& tile);

// Side of PNG tiles in pixels, whatever the level.
inline constexpr int kTilePngSide = 256;

// How far beyond its rectangle a PNG tile's points must come from, so that
// disks cut by the tile's edge are drawn whole across neighbouring tiles.
double TilePngMargin(const Tile& tile);

// A kTilePngSide square grey picture of the tile's rectangle, y up: white
// ground, each point a dark disk of radius d/4, R(p)/4 in a radius-field
// world (at least 0.75 pixel).
// `points` may include points beyond the rectangle (within TilePngMargin),
// which are drawn where they overlap it. INTERNAL if libpng fails.
StatusOr<std::string> RenderTilePng(const Tile& tile);

// 16 lower-case hex digits: how the formats and the world list show a
// world's fingerprint.
std::string FingerprintHex(uint64_t fingerprint);

// The strong ETag of a tile (quotes included): world fingerprint, generator
// version, format version, level, i, j and format.
std::string TileEtag(const World& world, const TileKey& key, TileFormat format);

}  // namespace scallop::server
