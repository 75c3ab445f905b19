// Parsing tile URLs: the path's segments, the tile indices, the query.
#include "server/tile_address.h"

#include <charconv>
#include <vector>

namespace scallop::server {
namespace {

constexpr std::string_view kPrefix = "/v1/worlds/";

std::vector<std::string_view> Split(std::string_view text, char separator) {
  std::vector<std::string_view> parts;
  for (size_t start = 0;;) {
    const size_t end = text.find(separator, start);
    parts.push_back(text.substr(start, end == std::string_view::npos ? end : end - start));
    if (end == std::string_view::npos) return parts;
    start = end + 1;
  }
}

int HexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

StatusOr<std::string> PercentDecode(std::string_view text, const char* field) {
  std::string decoded;
  for (size_t k = 0; k < text.size(); ++k) {
    if (text[k] != '%') {
      decoded += text[k];
      continue;
    }
    const int high = k + 2 < text.size() ? HexValue(text[k + 1]) : -1;
    const int low = high >= 0 ? HexValue(text[k + 2]) : -1;
    if (low < 0) return InvalidArgument(std::string(field) + ": bad percent-escape");
    decoded += static_cast<char>(high * 16 + low);
    k += 2;
  }
  return decoded;
}

// Tiles per half axis at `level`: regions -2^28 .. 2^28 - 1 tile the
// precision range exactly, so tiles -2^(28-level) .. 2^(28-level) - 1 do.
int64_t TilesPerHalfAxis(int level) { return kRegionsPerHalfAxis >> level; }

// A tile index: only what from_chars reads whole, and in canonical form (no
// leading zeros or "-0"), so that one tile has one URL for caches.
StatusOr<int64_t> ParseIndex(std::string_view text, const char* field, int level) {
  // (Built by append: GCC 12 warns falsely on "literal" + std::string.)
  std::string range = "-";
  range += std::to_string(TilesPerHalfAxis(level)) + ".." +
           std::to_string(TilesPerHalfAxis(level) - 1) + " at level " + std::to_string(level) +
           " (the precision range, 2^32 min_distance)";
  const std::string_view digits = text.starts_with('-') ? text.substr(1) : text;
  if (digits.empty() || digits.find_first_not_of("0123456789") != std::string_view::npos) {
    return InvalidArgument(std::string(field) + ": must be a decimal integer, got '" +
                           std::string(text.substr(0, 32)) + "'");
  }
  if ((digits.size() > 1 && digits[0] == '0') || text == "-0") {
    return InvalidArgument(std::string(field) + ": must be written without leading zeros or '-0'");
  }
  int64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error == std::errc::result_out_of_range) {
    return OutOfRange(std::string(field) + ": must be in " + range);
  }
  if (error != std::errc() || end != text.data() + text.size()) {
    return InvalidArgument(std::string(field) + ": must be a decimal integer");
  }
  if (value < -TilesPerHalfAxis(level) || value >= TilesPerHalfAxis(level)) {
    return OutOfRange(std::string(field) + ": must be in " + range + ", got " +
                      std::to_string(value));
  }
  return value;
}

std::optional<TileFormat> FormatNamed(std::string_view name) {
  for (TileFormat format : {TileFormat::kJson, TileFormat::kBinary, TileFormat::kPng}) {
    if (name == TileFormatName(format)) return format;
  }
  return std::nullopt;
}

// The Accept header's first known media type in our order of preference;
// q-values are not weighed (a browser's image request asks for image/png).
TileFormat FormatAccepted(std::string_view accept) {
  if (accept.find(TileContentType(TileFormat::kBinary)) != std::string_view::npos) {
    return TileFormat::kBinary;
  }
  if (accept.find(TileContentType(TileFormat::kJson)) != std::string_view::npos) {
    return TileFormat::kJson;
  }
  if (accept.find(TileContentType(TileFormat::kPng)) != std::string_view::npos) {
    return TileFormat::kPng;
  }
  return TileFormat::kJson;
}

}  // namespace

std::string_view TileFormatName(TileFormat format) {
  switch (format) {
    case TileFormat::kBinary:
      return "bin";
    case TileFormat::kPng:
      return "png";
    default:
      return "json";
  }
}

std::string_view TileContentType(TileFormat format) {
  switch (format) {
    case TileFormat::kBinary:
      return "application/vnd.scallop.tile";
    case TileFormat::kPng:
      return "image/png";
    default:
      return "application/json";
  }
}

bool IsTileTarget(std::string_view target) {
  const std::string_view path = target.substr(0, target.find('?'));
  return path.starts_with(kPrefix) && path.find("/tiles/") != std::string_view::npos;
}

StatusOr<TileAddress> ParseTileAddress(std::string_view target, std::string_view accept) {
  const size_t question = target.find('?');
  const std::string_view path = target.substr(0, question);
  const std::string_view query =
      question == std::string_view::npos ? std::string_view() : target.substr(question + 1);
  const std::string usage = "path: must be /v1/worlds/{world}/tiles/{i}/{j}[.json|.bin|.png]";
  if (!path.starts_with(kPrefix)) return InvalidArgument(usage);
  const std::vector<std::string_view> segments = Split(path.substr(kPrefix.size()), '/');
  if (segments.size() != 4 || segments[1] != "tiles" || segments[0].empty()) {
    return InvalidArgument(usage);
  }
  TileAddress address;
  StatusOr<std::string> world = PercentDecode(segments[0], "world");
  if (!world.ok()) return world.status();
  address.world = std::move(*world);

  std::optional<TileFormat> from_extension;
  std::string_view j_text = segments[3];
  if (const size_t dot = j_text.find('.'); dot != std::string_view::npos) {
    from_extension = FormatNamed(j_text.substr(dot + 1));
    if (!from_extension) {
      return InvalidArgument("path: the extension must be .json, .bin or .png, got '" +
                             std::string(j_text.substr(dot, 16)) + "'");
    }
    j_text = j_text.substr(0, dot);
  }

  std::optional<int> level;
  std::optional<TileFormat> from_query;
  if (!query.empty()) {
    for (const std::string_view parameter : Split(query, '&')) {
      const size_t equals = parameter.find('=');
      const std::string_view name = parameter.substr(0, equals);
      const std::string_view value =
          equals == std::string_view::npos ? std::string_view() : parameter.substr(equals + 1);
      if (name == "level") {
        int parsed = -1;
        const auto [end, error] =
            std::from_chars(value.data(), value.data() + value.size(), parsed);
        if (level || error != std::errc() || end != value.data() + value.size() || parsed < 0 ||
            parsed > kMaxTileLevel || (value.size() > 1 && value[0] == '0')) {
          return InvalidArgument("level: must be given once, an integer in 0.." +
                                 std::to_string(kMaxTileLevel));
        }
        level = parsed;
      } else if (name == "format") {
        from_query = FormatNamed(value);
        if (!from_query) return InvalidArgument("format: must be json, bin or png");
      } else {
        return InvalidArgument("query: unknown parameter '" + std::string(name.substr(0, 32)) +
                               "' (known: level, format)");
      }
    }
  }
  if (from_extension && from_query && *from_extension != *from_query) {
    return InvalidArgument("format: disagrees with the path's extension");
  }
  address.key.level = level.value_or(0);
  StatusOr<int64_t> i = ParseIndex(segments[2], "i", address.key.level);
  if (!i.ok()) return i.status();
  StatusOr<int64_t> j = ParseIndex(j_text, "j", address.key.level);
  if (!j.ok()) return j.status();
  address.key.i = *i;
  address.key.j = *j;
  address.format_in_url = from_extension || from_query;
  address.format = from_extension ? *from_extension
                   : from_query   ? *from_query
                                  : FormatAccepted(accept);
  return address;
}

Rect TileRect(const RegionLayout& layout, const TileKey& key) {
  const int64_t span = int64_t{1} << key.level;
  const Rect low = layout.RegionRect({key.i * span, key.j * span});
  const Rect high = layout.RegionRect({(key.i + 1) * span - 1, (key.j + 1) * span - 1});
  return {low.x0, low.y0, high.x1, high.y1};
}

}  // namespace scallop::server
