// The compact point encodings: the builder's set-up and the decoder.
#include "scallop/wire/point_encoding.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <string>

namespace scallop {
namespace {

// Little-endian, kBytes bytes: the width known at compile time, so the loop
// unrolls into a few loads and shifts.
template <int kBytes>
uint64_t ReadOffset(const char* at) {
  uint64_t value = 0;
  for (int b = 0; b < kBytes; ++b) {
    value |= static_cast<uint64_t>(static_cast<unsigned char>(at[b])) << (8 * b);
  }
  return value;
}

// The same as one 8-byte load and a mask, on a little-endian host with 8
// bytes readable at `at` (all but the last few offsets).
template <int kBytes>
uint64_t ReadOffsetWide(const char* at) {
  if constexpr (std::endian::native != std::endian::little) {
    return ReadOffset<kBytes>(at);
  } else {
    uint64_t value;
    std::memcpy(&value, at, sizeof value);
    return kBytes == 8 ? value : value & ((uint64_t{1} << (8 * kBytes)) - 1);
  }
}

// Writes axis `axis` of positions[0 .. count) from the offsets in `bytes`.
template <int kBytes>
void DecodeAxisAs(const char* bytes, size_t count, bool quantised, double edge, double quantum,
                  double Vec2::*axis, Vec2* positions) {
  // Offsets [0, wide) have 8 bytes readable from their start: two loops, so
  // the first has no test of which read to use.
  const size_t wide = count * kBytes >= 8 ? (count * kBytes - 8) / kBytes + 1 : 0;
  const uint64_t base = OrderedBits(edge);
  const auto decode = [&](uint64_t offset) {
    return quantised ? edge + (static_cast<double>(offset) + 0.5) * quantum
                     : FromOrderedBits(base + offset);
  };
  for (size_t n = 0; n < wide; ++n) {
    positions[n].*axis = decode(ReadOffsetWide<kBytes>(bytes + n * kBytes));
  }
  for (size_t n = wide; n < count; ++n) {
    positions[n].*axis = decode(ReadOffset<kBytes>(bytes + n * kBytes));
  }
}

void DecodeAxis(std::string_view bytes, int width, size_t count, bool quantised, double edge,
                double side, double Vec2::*axis, Vec2* positions) {
  const double quantum = std::ldexp(side, -8 * width);
  const char* data = bytes.data();
  switch (width) {
    case 1:
      return DecodeAxisAs<1>(data, count, quantised, edge, quantum, axis, positions);
    case 2:
      return DecodeAxisAs<2>(data, count, quantised, edge, quantum, axis, positions);
    case 3:
      return DecodeAxisAs<3>(data, count, quantised, edge, quantum, axis, positions);
    case 4:
      return DecodeAxisAs<4>(data, count, quantised, edge, quantum, axis, positions);
    case 5:
      return DecodeAxisAs<5>(data, count, quantised, edge, quantum, axis, positions);
    case 6:
      return DecodeAxisAs<6>(data, count, quantised, edge, quantum, axis, positions);
    case 7:
      return DecodeAxisAs<7>(data, count, quantised, edge, quantum, axis, positions);
    default:
      return DecodeAxisAs<8>(data, count, quantised, edge, quantum, axis, positions);
  }
}

std::string RegionName(int number) { return "encoded.regions[" + std::to_string(number) + "]"; }

Status CheckOffsets(int number, const char* axis, int width, size_t bytes, uint64_t count) {
  if (width < 1 || width > 8) {
    return InvalidArgument(RegionName(number) + "." + axis + "_offset_bytes: must be 1..8, got " +
                           std::to_string(width));
  }
  if (bytes != count * static_cast<uint64_t>(width)) {
    return InvalidArgument(RegionName(number) + "." + axis + "_offsets: " + std::to_string(bytes) +
                           " bytes, expected " + std::to_string(count) + " points of " +
                           std::to_string(width));
  }
  return Status::Ok();
}

}  // namespace

int ExactOffsetBytes(const RegionLayout& layout, int64_t k) {
  if (k == 0) return 8;
  const Rect owned = layout.RegionRect({k, k});
  const uint64_t largest = OrderedBits(owned.x1) - OrderedBits(owned.x0) - 1;
  return std::max(1, static_cast<int>(std::bit_width(largest) + 7) / 8);
}

EncodedRegionBuilder::EncodedRegionBuilder(PointEncoding encoding, const RegionLayout& layout,
                                           RegionKey key, size_t capacity)
    : quantised_(encoding == PointEncoding::kQuantised) {
  region_.key = key;
  const Rect owned = layout.RegionRect(key);
  if (quantised_) {
    region_.x_offset_bytes = region_.y_offset_bytes = kQuantisedOffsetBytes;
    quantum_ = std::ldexp(layout.side(), -8 * kQuantisedOffsetBytes);
    max_cell_ = std::ldexp(1.0, 8 * kQuantisedOffsetBytes) - 1;
  } else {
    region_.x_offset_bytes = ExactOffsetBytes(layout, key.i);
    region_.y_offset_bytes = ExactOffsetBytes(layout, key.j);
  }
  x_ = {&region_.x_offsets, 0, region_.x_offset_bytes, owned.x0, OrderedBits(owned.x0)};
  y_ = {&region_.y_offsets, 0, region_.y_offset_bytes, owned.y0, OrderedBits(owned.y0)};
  region_.x_offsets.resize(capacity * static_cast<size_t>(region_.x_offset_bytes) + 8);
  region_.y_offsets.resize(capacity * static_cast<size_t>(region_.y_offset_bytes) + 8);
}

EncodedRegion EncodedRegionBuilder::Take() && {
  region_.x_offsets.resize(x_.used);
  region_.y_offsets.resize(y_.used);
  return std::move(region_);
}

Status CheckEncodedPointsHeader(const EncodedPointsHeader& header) {
  if (header.encoding != PointEncoding::kExact && header.encoding != PointEncoding::kQuantised) {
    return InvalidArgument(
        "encoded.encoding: must be POINT_ENCODING_EXACT or POINT_ENCODING_QUANTISED");
  }
  if (!std::isfinite(header.region_side) || header.region_side <= 0) {
    return InvalidArgument("encoded.region_side: must be finite and > 0, got " +
                           std::to_string(header.region_side));
  }
  if (header.id_index_bits < 10 || header.id_index_bits > 24) {
    return InvalidArgument("encoded.id_index_bits: must be 10..24, got " +
                           std::to_string(header.id_index_bits));
  }
  return Status::Ok();
}

Status DecodeRegion(const EncodedPointsHeader& header, const EncodedRegionView& region, int number,
                    PlanePoints& points) {
  const std::span<const uint32_t> runs = region.index_runs;
  if (runs.size() % 2 != 0) {
    return InvalidArgument(RegionName(number) + ".index_runs: must be skip, take pairs, got " +
                           std::to_string(runs.size()) + " numbers");
  }
  // 64-bit sums of 32-bit counts cannot overflow.
  uint64_t count = 0, end = 0;  // points, and one past the last index
  for (size_t r = 0; r < runs.size(); r += 2) {
    count += runs[r + 1];
    end += uint64_t{runs[r]} + runs[r + 1];
  }
  if (end > (uint64_t{1} << header.id_index_bits)) {
    return InvalidArgument(RegionName(number) + ".index_runs: index " + std::to_string(end - 1) +
                           " beyond 2^" + std::to_string(header.id_index_bits));
  }
  if (Status status =
          CheckOffsets(number, "x", region.x_offset_bytes, region.x_offsets.size(), count);
      !status.ok()) {
    return status;
  }
  if (Status status =
          CheckOffsets(number, "y", region.y_offset_bytes, region.y_offsets.size(), count);
      !status.ok()) {
    return status;
  }

  const size_t first = points.positions.size();
  // Growth stays geometric (resize, push_back): an exact reserve per region
  // would copy everything decoded so far once per region.
  points.positions.resize(first + count);
  points.ids.resize(first + count);
  uint64_t* id = points.ids.data() + first;
  uint64_t next = EncodePointId(region.key, 0, header.id_index_bits);
  for (size_t r = 0; r < runs.size(); r += 2) {
    next += runs[r];
    for (uint32_t t = 0; t < runs[r + 1]; ++t) *id++ = next++;
  }
  // The edges by RegionLayout's own expression (k * S), so that they are
  // the encoder's to the bit: S / 16 * 16 is S exactly.
  const Rect owned = RegionLayout(header.region_side / kRegionSideInD).RegionRect(region.key);
  const bool quantised = header.encoding == PointEncoding::kQuantised;
  Vec2* out = points.positions.data() + first;
  DecodeAxis(region.x_offsets, region.x_offset_bytes, count, quantised, owned.x0,
             header.region_side, &Vec2::x, out);
  DecodeAxis(region.y_offsets, region.y_offset_bytes, count, quantised, owned.y0,
             header.region_side, &Vec2::y, out);
  return Status::Ok();
}

}  // namespace scallop
