// Points messages in the compact encodings (Points.encoded, docs/wire.md):
// the request's PointEncoding checked, scallopd's writer of encoded points,
// and the reader the client library decodes them with. The codec itself is
// the core's (scallop/wire/point_encoding.h); this file moves its regions in
// and out of messages.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "scallop/base/status.h"
#include "scallop/plane/world.h"
#include "scallop/v1/scallop.pb.h"
#include "scallop/wire/point_encoding.h"
#include "world_messages.h"

namespace scallop {

// The request's encoding: UNSPECIFIED and PACKED are kPacked. A value this
// build does not know is INVALID_ARGUMENT naming `field` ("encoding"). O(1).
StatusOr<PointEncoding> PointEncodingFromMessage(int value, std::string_view field = "encoding");
v1::PointEncoding PointEncodingToMessage(PointEncoding encoding);

// Writes points into message.encoded region by region, as they are
// appended in the API's order (regions one after another, indices
// ascending within each); with a field (a field world's), each point's R
// into radii as PointsAppender does. The last region is written when the
// appender goes: use the message only after. Not thread-safe.
// A layered world's points are written layer by layer (StartLayer before
// each layer's): encoded.layers holds every layer's region side and index
// bits, each region its layer, and radii each point's spacing in its layer
// when LayeredPointsCarryRadii (world_messages.h).
// REQUIRES: encoding is kExact or kQuantised; every point owned by the
// region its id names (as every point the engine returns is).
class EncodedPointsAppender {
 public:
  EncodedPointsAppender(v1::Points& message, PointEncoding encoding, const World& world,
                        size_t capacity);
  ~EncodedPointsAppender();
  EncodedPointsAppender(const EncodedPointsAppender&) = delete;
  EncodedPointsAppender& operator=(const EncodedPointsAppender&) = delete;

  // The points appended next are layer `layer`'s (-1: the world has no layers; nothing
  // changes). REQUIRES: a layered world for layer >= 0.
  void StartLayer(int layer);

  void Append(Vec2 position, uint64_t id) {
    // Ids of one region share their high bits; the next region's differ.
    const uint64_t region_bits = id >> index_bits_;
    if (!builder_ || region_bits != region_bits_) StartRegion(position, region_bits);
    builder_->Add(static_cast<uint32_t>(id & index_mask_), position);
    if (field_ != nullptr) {
      message_.add_radii(field_->Evaluate(position));
    } else if (radii_world_ != nullptr) {
      message_.add_radii(radii_world_->SpacingAt(position));
    }
  }

 private:
  void StartRegion(Vec2 position, uint64_t region_bits);
  void FinishRegion();

  v1::Points& message_;
  v1::EncodedPoints& encoded_;
  PointEncoding encoding_;
  const World& world_;
  RegionLayout layout_;
  const RadiusField* field_;
  int index_bits_;
  uint64_t index_mask_;
  size_t capacity_;  // points still expected, at most
  uint32_t layer_ = 0;
  const World* radii_world_ = nullptr;  // a layered world's current layer, when radii go along
  uint64_t region_bits_ = 0;
  std::optional<EncodedRegionBuilder> builder_;  // the region being written
};

// Calls fill(appender) with the appender of `encoding`: PointsAppender for
// kPacked (with room for `capacity` points), EncodedPointsAppender for the
// others. Both have Append(Vec2 position, uint64_t id), so one loop serves
// every encoding without a virtual call a point.
template <typename Fill>
void WritePoints(v1::Points& message, PointEncoding encoding, const World& world, size_t capacity,
                 Fill fill) {
  if (encoding == PointEncoding::kPacked) {
    PointsAppender appender(message, capacity, world);
    fill(appender);
  } else {
    EncodedPointsAppender appender(message, encoding, world, capacity);
    fill(appender);
  }
}

// Points [begin, end) of `points` (one query's, in its order) written in `encoding`; a layered
// world's with their layers (points.layers).
void AppendPoints(const PlanePoints& points, size_t begin, size_t end, v1::Points& message,
                  const World& world, PointEncoding encoding);

// The message's encoded points appended to `points`, ids made from the
// regions; with encoded.layers (a layered world), each point's layer, its
// region's, appended to points.layers. INVALID_ARGUMENT naming the field
// (encoded.regions[3].x_offsets, encoded.regions[3].layer,
// encoded.layers[1].region_side) when the message is malformed
// (DecodeRegion); nothing is appended then. O(points).
Status ReadEncodedPoints(const v1::EncodedPoints& message, PlanePoints& points);

}  // namespace scallop
