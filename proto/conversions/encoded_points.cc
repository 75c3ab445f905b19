// The compact encodings in and out of Points messages.
#include "encoded_points.h"

#include <algorithm>
#include <string>
#include <vector>

#include "scallop/plane/layer_regions.h"
#include "scallop/plane/world_layers.h"

namespace scallop {

StatusOr<PointEncoding> PointEncodingFromMessage(int value, std::string_view field) {
  switch (value) {
    case v1::POINT_ENCODING_UNSPECIFIED:
    case v1::POINT_ENCODING_PACKED:
      return PointEncoding::kPacked;
    case v1::POINT_ENCODING_EXACT:
      return PointEncoding::kExact;
    case v1::POINT_ENCODING_QUANTISED:
      return PointEncoding::kQuantised;
    default:
      return InvalidArgument(std::string(field) +
                             ": must be POINT_ENCODING_PACKED, POINT_ENCODING_EXACT or "
                             "POINT_ENCODING_QUANTISED (or unset), got " +
                             std::to_string(value));
  }
}

v1::PointEncoding PointEncodingToMessage(PointEncoding encoding) {
  switch (encoding) {
    case PointEncoding::kExact:
      return v1::POINT_ENCODING_EXACT;
    case PointEncoding::kQuantised:
      return v1::POINT_ENCODING_QUANTISED;
    case PointEncoding::kPacked:
      break;
  }
  return v1::POINT_ENCODING_PACKED;
}

EncodedPointsAppender::EncodedPointsAppender(v1::Points& message, PointEncoding encoding,
                                             const World& world, size_t capacity)
    : message_(message),
      encoded_(*message.mutable_encoded()),
      encoding_(encoding),
      world_(world),
      layout_(WorldOfLayer(world, world.layers() != nullptr ? 0 : -1)),
      field_(world.radius_field()),
      index_bits_(layout_.point_id_index_bits()),
      index_mask_((uint64_t{1} << index_bits_) - 1),
      capacity_(capacity) {
  encoded_.set_encoding(PointEncodingToMessage(encoding));
  const WorldLayers* layers = world.layers();
  if (layers == nullptr) {
    encoded_.set_region_side(layout_.side());
    encoded_.set_id_index_bits(static_cast<uint32_t>(index_bits_));
  } else if (encoded_.layers_size() == 0) {
    // region_side and id_index_bits stay 0: a decoder unaware of layers fails loudly.
    for (int k = 0; k < layers->count(); ++k) {
      const RegionLayout layout(layers->world(k));
      v1::EncodedLayer& layer = *encoded_.add_layers();
      layer.set_region_side(layout.side());
      layer.set_id_index_bits(static_cast<uint32_t>(layout.point_id_index_bits()));
    }
    if (LayeredPointsCarryRadii(world)) radii_world_ = &layers->world(0);
  }
  if (field_ != nullptr || radii_world_ != nullptr) {
    message.mutable_radii()->Reserve(message.radii_size() + static_cast<int>(capacity));
  }
}

void EncodedPointsAppender::StartLayer(int layer) {
  if (layer < 0) return;
  FinishRegion();
  const World& own = world_.layers()->world(layer);
  layer_ = static_cast<uint32_t>(layer);
  layout_ = RegionLayout(own);
  index_bits_ = layout_.point_id_index_bits();
  index_mask_ = (uint64_t{1} << index_bits_) - 1;
  if (radii_world_ != nullptr) radii_world_ = &own;
}

EncodedPointsAppender::~EncodedPointsAppender() { FinishRegion(); }

void EncodedPointsAppender::StartRegion(Vec2 position, uint64_t region_bits) {
  FinishRegion();
  region_bits_ = region_bits;
  // Room for a whole constant-world region (296 points) or what is left.
  builder_.emplace(encoding_, layout_, layout_.RegionOf(position.x, position.y),
                   std::min<size_t>(capacity_, 320));
}

void EncodedPointsAppender::FinishRegion() {
  if (!builder_) return;
  capacity_ -= std::min(capacity_, builder_->count());
  EncodedRegion region = std::move(*builder_).Take();
  builder_.reset();
  v1::EncodedRegion& message = *encoded_.add_regions();
  message.set_i(region.key.i);
  message.set_j(region.key.j);
  message.mutable_index_runs()->Add(region.index_runs.begin(), region.index_runs.end());
  message.set_x_offset_bytes(static_cast<uint32_t>(region.x_offset_bytes));
  message.set_y_offset_bytes(static_cast<uint32_t>(region.y_offset_bytes));
  message.set_x_offsets(std::move(region.x_offsets));
  message.set_y_offsets(std::move(region.y_offsets));
  message.set_layer(layer_);
}

void AppendPoints(const PlanePoints& points, size_t begin, size_t end, v1::Points& message,
                  const World& world, PointEncoding encoding) {
  WritePoints(message, encoding, world, end - begin, [&](auto& appender) {
    int layer = -1;
    for (size_t k = begin; k < end; ++k) {
      if (!points.layers.empty() && points.layers[k] != layer) {
        layer = points.layers[k];
        appender.StartLayer(layer);
      }
      appender.Append(points.positions[k], points.ids[k]);
    }
  });
}

namespace {

StatusOr<EncodedPointsHeader> HeaderOf(PointEncoding encoding, double region_side,
                                       uint32_t id_index_bits, const std::string& where) {
  const EncodedPointsHeader header{
      .encoding = encoding,
      .region_side = region_side,
      .id_index_bits = static_cast<int>(std::min<uint32_t>(id_index_bits, 64))};
  Status status = CheckEncodedPointsHeader(header);
  if (status.ok()) return header;
  // "encoded.region_side: ..." names a layer's field as "encoded.layers[1].region_side: ...".
  std::string message = status.message();
  if (message.starts_with("encoded.")) message = where + message.substr(8);
  return InvalidArgument(message);
}

}  // namespace

Status ReadEncodedPoints(const v1::EncodedPoints& message, PlanePoints& points) {
  StatusOr<PointEncoding> encoding =
      PointEncodingFromMessage(message.encoding(), "encoded.encoding");
  if (!encoding.ok()) return encoding.status();
  // One header a layer for a layered world; one for the message otherwise.
  std::vector<EncodedPointsHeader> headers;
  const bool layered = message.layers_size() != 0;
  if (!layered) {
    StatusOr<EncodedPointsHeader> header =
        HeaderOf(*encoding, message.region_side(), message.id_index_bits(), "encoded.");
    if (!header.ok()) return header.status();
    headers.push_back(*header);
  }
  for (int k = 0; k < message.layers_size() && k < 256; ++k) {
    StatusOr<EncodedPointsHeader> header =
        HeaderOf(*encoding, message.layers(k).region_side(), message.layers(k).id_index_bits(),
                 "encoded.layers[" + std::to_string(k) + "].");
    if (!header.ok()) return header.status();
    headers.push_back(*header);
  }
  // Room for every point at once, counted from the bytes that hold them (so
  // a message cannot make us reserve more than it carries).
  size_t room = 0;
  for (const v1::EncodedRegion& region : message.regions()) {
    room += region.x_offsets().size() / std::max<uint32_t>(region.x_offset_bytes(), 1);
  }
  const size_t first = points.ids.size();
  const size_t first_layer = points.layers.size();
  points.positions.reserve(points.positions.size() + room);
  points.ids.reserve(points.ids.size() + room);
  const auto fail = [&](Status status) {
    points.positions.resize(first);
    points.ids.resize(first);
    points.layers.resize(first_layer);
    return status;
  };
  for (int r = 0; r < message.regions_size(); ++r) {
    const v1::EncodedRegion& region = message.regions(r);
    if (region.layer() >= headers.size()) {
      return fail(InvalidArgument("encoded.regions[" + std::to_string(r) + "].layer: " +
                                  (layered ? "must be below the count of encoded.layers"
                                           : "must be 0 without encoded.layers")));
    }
    const EncodedRegionView view{
        .key = {region.i(), region.j()},
        .index_runs = {region.index_runs().data(), static_cast<size_t>(region.index_runs_size())},
        .x_offset_bytes = static_cast<int>(std::min<uint32_t>(region.x_offset_bytes(), 64)),
        .y_offset_bytes = static_cast<int>(std::min<uint32_t>(region.y_offset_bytes(), 64)),
        .x_offsets = region.x_offsets(),
        .y_offsets = region.y_offsets()};
    if (Status status = DecodeRegion(headers[region.layer()], view, r, points); !status.ok()) {
      return fail(status);
    }
    if (layered) points.layers.resize(points.ids.size(), static_cast<uint8_t>(region.layer()));
  }
  return Status::Ok();
}

}  // namespace scallop
