// Writing tiles as JSON, binary and PNG (formats in docs/tiles.md).
#include "server/tile_encoding.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iterator>

#include "scallop/image/png_image.h"
#include "scallop/plane/world_layers.h"

namespace scallop::server {
namespace {

// NumberText's rule (scallop/base/number_text.h), appended in place: a
// level-5 tile has half a million coordinates.
void AppendNumber(std::string& out, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

void AppendInteger(std::string& out, int64_t value) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

void AppendUnsigned(std::string& out, uint64_t value) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

// JSON string of a world name: quotes, backslashes and control characters
// escaped; other bytes as they are (names come from the configuration).
void AppendJsonString(std::string& out, const std::string& text) {
  out += '"';
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char escape[8];
      std::snprintf(escape, sizeof escape, "\\u%04x", static_cast<unsigned>(c));
      out += escape;
    } else {
      out += c;
    }
  }
  out += '"';
}

template <typename Unsigned>
void AppendLittleEndian(std::string& out, Unsigned value) {
  for (size_t byte = 0; byte < sizeof value; ++byte) {
    out += static_cast<char>(static_cast<uint64_t>(value) >> (8 * byte) & 0xff);
  }
}

void AppendDouble(std::string& out, double value) {
  uint64_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  AppendLittleEndian(out, bits);
}

}  // namespace

std::string EncodeTileJson(const Tile& tile) {
  std::string out;
  // About 20 bytes an id and 20 a coordinate.
  out.reserve(256 + tile.ids.size() * 64);
  out += "{\"world\":";
  AppendJsonString(out, tile.world_name);
  out += ",\"level\":";
  AppendInteger(out, tile.key.level);
  out += ",\"i\":";
  AppendInteger(out, tile.key.i);
  out += ",\"j\":";
  AppendInteger(out, tile.key.j);
  out += ",\"rect\":[";
  AppendNumber(out, tile.rect.x0);
  out += ',';
  AppendNumber(out, tile.rect.y0);
  out += ',';
  AppendNumber(out, tile.rect.x1);
  out += ',';
  AppendNumber(out, tile.rect.y1);
  out += "],\"fingerprint\":\"" + FingerprintHex(tile.world.fingerprint()) + "\"";
  out += ",\"generator_version\":";
  AppendInteger(out, tile.world.generator_version());
  out += ",\"min_distance\":";
  AppendNumber(out, tile.world.min_distance());
  out += ",\"count\":";
  AppendInteger(out, static_cast<int64_t>(tile.ids.size()));
  out += ",\"ids\":[";
  for (size_t k = 0; k < tile.ids.size(); ++k) {
    if (k > 0) out += ',';
    out += '"';
    AppendUnsigned(out, tile.ids[k]);
    out += '"';
  }
  const bool radii = tile.world.radius_field() != nullptr || tile.world.layers() != nullptr;
  for (const auto& [name, values] :
       {std::pair{"xs", &tile.xs}, {"ys", &tile.ys}, {"rs", &tile.rs}}) {
    if (values == &tile.rs && !radii) break;
    out += "],\"";
    out += name;
    out += "\":[";
    for (size_t k = 0; k < values->size(); ++k) {
      if (k > 0) out += ',';
      AppendNumber(out, (*values)[k]);
    }
  }
  if (tile.world.layers() != nullptr) {
    out += "],\"layers\":[";
    for (size_t k = 0; k < tile.layers.size(); ++k) {
      if (k > 0) out += ',';
      AppendInteger(out, tile.layers[k]);
    }
    out += "],\"layer_names\":[";
    for (size_t k = 0; k < tile.layer_names.size(); ++k) {
      if (k > 0) out += ',';
      AppendJsonString(out, tile.layer_names[k]);
    }
  }
  out += "]}";
  return out;
}

std::string EncodeTileBinary(const Tile& tile) {
  std::string out;
  const bool layered = tile.world.layers() != nullptr;
  const bool radii = tile.world.radius_field() != nullptr || layered;
  out.reserve(80 + tile.ids.size() * (radii ? 34 : 24));
  out += "SCTL";
  AppendLittleEndian(out, uint16_t{1});  // binary layout version
  // Flags: bit 0, an rs array follows ys (radius-field and layered worlds); bit 1, a layers
  // array follows (layered worlds).
  AppendLittleEndian(out, static_cast<uint16_t>((radii ? 1 : 0) | (layered ? 2 : 0)));
  AppendLittleEndian(out, static_cast<uint32_t>(tile.ids.size()));
  AppendLittleEndian(out, static_cast<uint32_t>(tile.key.level));
  AppendLittleEndian(out, static_cast<uint64_t>(tile.key.i));
  AppendLittleEndian(out, static_cast<uint64_t>(tile.key.j));
  AppendLittleEndian(out, tile.world.fingerprint());
  AppendLittleEndian(out, tile.world.generator_version());
  AppendLittleEndian(out, uint32_t{0});  // reserved
  AppendDouble(out, tile.rect.x0);
  AppendDouble(out, tile.rect.y0);
  AppendDouble(out, tile.rect.x1);
  AppendDouble(out, tile.rect.y1);
  for (const uint64_t id : tile.ids) AppendLittleEndian(out, id);
  for (const double x : tile.xs) AppendDouble(out, x);
  for (const double y : tile.ys) AppendDouble(out, y);
  if (radii) {
    for (const double r : tile.rs) AppendDouble(out, r);
  }
  if (layered) {
    for (const uint16_t layer : tile.layers) AppendLittleEndian(out, layer);
  }
  return out;
}

int TileFormatVersion(const World& world) {
  return world.layers() != nullptr ? kLayeredTileFormatVersion : kTileFormatVersion;
}

uint32_t TileLayerColour(int layer) {
  static constexpr uint32_t kColours[] = {0x2e7d32, 0x8d6e63, 0x546e7a, 0xc62828,
                                          0x6a1b9a, 0x1565c0, 0xef6c00, 0x00838f};
  return kColours[static_cast<size_t>(layer) % std::size(kColours)];
}

double TilePngMargin(const Tile& tile) {
  const double pixel = tile.rect.Width() / kTilePngSide;
  // The largest disk: d/4, or r_max/4 in a radius-field world, a layered world's largest
  // spacing / 4.
  const double spacing = tile.world.layers() != nullptr ? tile.world.layers()->largest_spacing()
                                                        : tile.world.max_spacing();
  return std::max(0.25 * spacing, 0.75 * pixel) + pixel;
}

StatusOr<std::string> RenderTilePng(const Tile& tile) {
  constexpr uint8_t kGround = 255;
  constexpr uint8_t kPoint = 40;
  // Grey for one kind of point; a layered world's in colour, a colour a layer.
  const int channels = tile.layers.empty() ? 1 : 3;
  Image8 image{.width = kTilePngSide,
               .height = kTilePngSide,
               .channels = channels,
               .pixels = std::vector<uint8_t>(
                   static_cast<size_t>(kTilePngSide) * kTilePngSide * static_cast<size_t>(channels),
                   kGround)};
  const double pixel = tile.rect.Width() / kTilePngSide;  // tiles are square
  // Pixel (column c, row r) has its centre at (x0 + (c + 0.5) pixel,
  // y1 - (r + 0.5) pixel): row 0 is the top.
  for (size_t k = 0; k < tile.xs.size(); ++k) {
    const double spacing = tile.rs.empty() ? tile.world.min_distance() : tile.rs[k];
    const double radius = std::max(0.25 * spacing, 0.75 * pixel);
    const double u = (tile.xs[k] - tile.rect.x0) / pixel;  // in pixels from the left
    const double v = (tile.rect.y1 - tile.ys[k]) / pixel;  // in pixels from the top
    const double reach = radius / pixel;
    const int c0 = std::max(0, static_cast<int>(std::floor(u - reach)));
    const int c1 = std::min(kTilePngSide - 1, static_cast<int>(std::floor(u + reach)));
    const int r0 = std::max(0, static_cast<int>(std::floor(v - reach)));
    const int r1 = std::min(kTilePngSide - 1, static_cast<int>(std::floor(v + reach)));
    const uint32_t colour = channels == 1 ? 0 : TileLayerColour(tile.layers[k]);
    for (int r = r0; r <= r1; ++r) {
      for (int c = c0; c <= c1; ++c) {
        const double du = c + 0.5 - u, dv = r + 0.5 - v;
        if (du * du + dv * dv > reach * reach) continue;
        const size_t at = (static_cast<size_t>(r) * kTilePngSide + static_cast<size_t>(c)) *
                          static_cast<size_t>(channels);
        if (channels == 1) {
          image.pixels[at] = kPoint;
        } else {
          for (int channel = 0; channel < 3; ++channel) {
            image.pixels[at + static_cast<size_t>(channel)] =
                static_cast<uint8_t>(colour >> (16 - 8 * channel));
          }
        }
      }
    }
  }
  StatusOr<std::string> png = EncodePng(image);
  if (!png.ok()) return Status(StatusCode::kInternal, "tile: " + png.status().message());
  return png;
}

std::string FingerprintHex(uint64_t fingerprint) {
  char buffer[17];
  std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(fingerprint));
  return buffer;
}

std::string TileEtag(const World& world, const TileKey& key, TileFormat format) {
  std::string etag = "\"";
  return etag + FingerprintHex(world.fingerprint()) + ".g" +
         std::to_string(world.generator_version()) + ".t" +
         std::to_string(TileFormatVersion(world)) + ".L" + std::to_string(key.level) + "." +
         std::to_string(key.i) + "." + std::to_string(key.j) + "." +
         std::string(TileFormatName(format)) + "\"";
}

}  // namespace scallop::server
