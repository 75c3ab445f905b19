// The compact encodings of points on the wire (docs/wire.md): a region's
// points as the indices they hold in the region (the id's low bits, so ids
// need not be sent) and each coordinate as an offset from the region's low
// edge, either exact to the bit or quantised. No protobuf here: scallopd's
// encoder and the client library's decoder are this one codec.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "scallop/base/status.h"
#include "scallop/geometry/vec2.h"
#include "scallop/plane/plane_engine.h"
#include "scallop/plane/region_layout.h"

namespace scallop {

// kPacked is the API's packed arrays (24 bytes a point), which this codec
// does not touch; the others are compact.
//  - kExact: an offset is the number of doubles from the region's low edge
//    to the coordinate, taken modulo 2^64 (OrderedBits(x) - OrderedBits(edge)),
//    in ExactOffsetBytes bytes: decodes to the same double, bit for bit.
//    In one binade that is (x - edge) / ulp(x), so it costs about
//    log2(S / ulp(x)) bits: 7 bytes a coordinate within 2^8 d of the
//    origin, 5 at 1e6 d, 4 at 1e9 d; 8 in the regions on either side of 0
//    (k = 0 and -1), where doubles get as fine as subnormals.
//  - kQuantised: an offset is floor((x - edge) / q), q = S / 2^16, in 2
//    bytes, decoded to the cell's centre edge + (n + 0.5) q: within q / 2 of
//    the coordinate (2^-13 d for a constant world), plus the rounding of the
//    decoding sum (at most ulp(x) + ulp(S); 2^-20 d at 2^32 d).
enum class PointEncoding { kPacked, kExact, kQuantised };

// Bytes of a quantised offset: 2, so the quantum is S / 2^16.
inline constexpr int kQuantisedOffsetBytes = 2;

// A monotone bijection of doubles onto uint64 (-0.0 just below +0.0; NaNs
// at the ends), so that consecutive doubles map to consecutive integers:
// a sign bit of 0 is set, a sign bit of 1 flips every bit. Branch-free.
constexpr uint64_t OrderedBits(double value) {
  const auto bits = std::bit_cast<uint64_t>(value);
  return bits ^ ((uint64_t{0} - (bits >> 63)) | (uint64_t{1} << 63));
}
constexpr double FromOrderedBits(uint64_t bits) {
  return std::bit_cast<double>(bits ^ (((bits >> 63) - 1) | (uint64_t{1} << 63)));
}

// Bytes an exact offset takes on an axis of region index `k` (i or j) of
// `layout`: enough for the count of doubles in [Edge(k), Edge(k + 1)), and
// 8 for k = 0, where -0.0 lies one below the edge (offsets wrap). O(1).
int ExactOffsetBytes(const RegionLayout& layout, int64_t k);

// One region's points, encoded: what the API's EncodedRegion message holds.
// index_runs alternate skip and take counts: the points' indices are those
// taken, counting from 0 (skip 3, take 2, skip 1, take 1: 3, 4, 6). Offsets
// are x_offset_bytes (y_offset_bytes) little-endian bytes a point, in index
// order.
struct EncodedRegion {
  RegionKey key;
  std::vector<uint32_t> index_runs;
  int x_offset_bytes = 0;
  int y_offset_bytes = 0;
  std::string x_offsets;
  std::string y_offsets;
};

// Builds one EncodedRegion from points added in ascending index order.
// Cost: O(1) a point (a few integer operations, or one division for
// kQuantised). Not thread-safe; one builder per region.
class EncodedRegionBuilder {
 public:
  // REQUIRES: encoding is kExact or kQuantised.
  EncodedRegionBuilder(PointEncoding encoding, const RegionLayout& layout, RegionKey key,
                       size_t capacity = 0);
  // Not copied or moved: the axes point into the region being built.
  EncodedRegionBuilder(const EncodedRegionBuilder&) = delete;
  EncodedRegionBuilder& operator=(const EncodedRegionBuilder&) = delete;

  // REQUIRES: index above the previous one's; position in the region's
  // rectangle (layout.RegionRect(key)), as every point the region owns is.
  void Add(uint32_t index, Vec2 position) {
    if (index != next_index_ || region_.index_runs.empty()) {
      region_.index_runs.push_back(index - next_index_);  // skip
      region_.index_runs.push_back(0);                    // take
    }
    ++region_.index_runs.back();
    next_index_ = index + 1;
    x_.Put(Offset(position.x, x_));
    y_.Put(Offset(position.y, y_));
    ++count_;
  }

  size_t count() const { return count_; }
  RegionKey key() const { return region_.key; }

  // The region encoded so far; the builder is spent.
  EncodedRegion Take() &&;

 private:
  // One axis's offsets: written 8 bytes at a time into room with 8 bytes to
  // spare (one store), advanced by the offset's width; cut at Take.
  struct Axis {
    std::string* bytes = nullptr;  // the region's own x_offsets or y_offsets
    size_t used = 0;
    int width = 0;
    double edge = 0;
    uint64_t edge_bits = 0;  // OrderedBits(edge)
    void Put(uint64_t offset) {
      if (used + 8 > bytes->size()) bytes->resize(std::max<size_t>(64, 2 * bytes->size()));
      char* at = bytes->data() + used;
      for (int b = 0; b < 8; ++b) at[b] = static_cast<char>(offset >> (8 * b));
      used += static_cast<size_t>(width);
    }
  };

  uint64_t Offset(double value, const Axis& axis) const {
    if (!quantised_) return OrderedBits(value) - axis.edge_bits;
    const double cells = (value - axis.edge) / quantum_;
    // Negative only for -0.0 in a region whose edge is +0.0 (cells is -0.0).
    return cells <= 0           ? 0
           : cells >= max_cell_ ? static_cast<uint64_t>(max_cell_)
                                : static_cast<uint64_t>(cells);
  }

  EncodedRegion region_;
  Axis x_, y_;
  bool quantised_;
  double quantum_ = 0;
  double max_cell_ = 0;
  uint32_t next_index_ = 0;
  size_t count_ = 0;
};

// What a decoder needs besides the regions: the message's encoding, region
// side S (world units) and id index bits b (point_id.h).
struct EncodedPointsHeader {
  PointEncoding encoding = PointEncoding::kExact;
  double region_side = 0;
  int id_index_bits = 0;
};

// A region as it arrives, viewed in place (the message's own arrays).
struct EncodedRegionView {
  RegionKey key;
  std::span<const uint32_t> index_runs;
  int x_offset_bytes = 0;
  int y_offset_bytes = 0;
  std::string_view x_offsets;
  std::string_view y_offsets;
};

// INVALID_ARGUMENT naming the field ("encoded.region_side: ...") unless the
// header can be decoded: kExact or kQuantised, S finite and > 0, b in
// [10, 24]. O(1).
Status CheckEncodedPointsHeader(const EncodedPointsHeader& header);

// Appends the region's points to `points` (positions, and ids made from the
// region, index and b), in index order. INVALID_ARGUMENT naming the field
// (as the API names it: "encoded.regions[N].index_runs", N = `number`, the
// region's place in its message) when the runs are not
// skip/take pairs, an index reaches 2^b, an offset width is outside 1..8,
// or the offsets' lengths differ from points x width; nothing is appended
// then. REQUIRES: CheckEncodedPointsHeader(header) is ok. O(points).
Status DecodeRegion(const EncodedPointsHeader& header, const EncodedRegionView& region, int number,
                    PlanePoints& points);

}  // namespace scallop
