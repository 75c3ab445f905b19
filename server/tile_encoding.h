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
// Layered worlds' tiles (issue 19) carry each point's layer and spacing and
// draw each layer in its colour: version 4, for them alone, so that the
// other worlds' tiles and ETags stay version 3's.
inline constexpr int kLayeredTileFormatVersion = 4;
// The format version of `world`'s tiles, in its ETags.
int TileFormatVersion(const World& world);

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
  // there, as Points.radii carries it), or of a layered world (each point's
  // spacing in its layer); empty for other worlds.
  std::vector<double> rs;
  // A layered world's: each point's layer (its number in the world's order),
  // and the layers' names. Empty for other worlds.
  std::vector<uint16_t> layers;
  std::vector<std::string> layer_names;
};

// {"world", "level", "i", "j", "rect", "fingerprint", "generator_version",
// "min_distance", "count", "ids" (decimal strings), "xs", "ys", for a
// radius-field or layered world "rs", and for a layered world "layers" (each
// point's layer number) and "layer_names" (listed once)}; numbers are the
// shortest text that reads back to the same double.
std::string EncodeTileJson(const Tile& tile);

// The 80-byte header, then ids (u64), xs and ys (f64), for a radius-field or
// layered world rs (f64, flag bit 0), and for a layered world layers (u16,
// flag bit 1), all little-endian.
std::string EncodeTileBinary(const Tile& tile);

// Side of PNG tiles in pixels, whatever the level.
inline constexpr int kTilePngSide = 256;

// How far beyond its rectangle a PNG tile's points must come from, so that
// disks cut by the tile's edge are drawn whole across neighbouring tiles.
double TilePngMargin(const Tile& tile);

// A kTilePngSide square grey picture of the tile's rectangle, y up: white
// ground, each point a dark disk of radius d/4, R(p)/4 in a radius-field
// world (at least 0.75 pixel). A layered world's is in colour: each layer's
// disks (at a quarter of the point's spacing) in the layer's colour
// (TileLayerColour), later layers over earlier ones.
// `points` may include points beyond the rectangle (within TilePngMargin),
// which are drawn where they overlap it. INTERNAL if libpng fails.
StatusOr<std::string> RenderTilePng(const Tile& tile);

// Layer k's colour in PNG tiles and the viewer, as 0xRRGGBB: distinct at a
// glance and dark enough on white (the CLI's SVG palette).
uint32_t TileLayerColour(int layer);

// 16 lower-case hex digits: how the formats and the world list show a
// world's fingerprint.
std::string FingerprintHex(uint64_t fingerprint);

// The strong ETag of a tile (quotes included): world fingerprint, generator
// version, format version, level, i, j and format.
std::string TileEtag(const World& world, const TileKey& key, TileFormat format);

}  // namespace scallop::server
