// The compact encodings in and out of Points messages.
#include "encoded_points.h"

#include <algorithm>
#include <string>

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
      layout_(world),
      field_(world.radius_field()),
      index_bits_(layout_.point_id_index_bits()),
      index_mask_((uint64_t{1} << index_bits_) - 1),
      capacity_(capacity) {
  encoded_.set_encoding(PointEncodingToMessage(encoding));
  encoded_.set_region_side(layout_.side());
  encoded_.set_id_index_bits(static_cast<uint32_t>(index_bits_));
  if (field_ != nullptr) message.mutable_radii()->Reserve(message.radii_size() + capacity);
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
}

void AppendPoints(const PlanePoints& points, size_t begin, size_t end, v1::Points& message,
                  const World& world, PointEncoding encoding) {
  WritePoints(message, encoding, world, end - begin, [&](auto& appender) {
    for (size_t k = begin; k < end; ++k) appender.Append(points.positions[k], points.ids[k]);
  });
}

Status ReadEncodedPoints(const v1::EncodedPoints& message, PlanePoints& points) {
  StatusOr<PointEncoding> encoding =
      PointEncodingFromMessage(message.encoding(), "encoded.encoding");
  if (!encoding.ok()) return encoding.status();
  const EncodedPointsHeader header{
      .encoding = *encoding,
      .region_side = message.region_side(),
      .id_index_bits = static_cast<int>(std::min<uint32_t>(message.id_index_bits(), 64))};
  if (Status status = CheckEncodedPointsHeader(header); !status.ok()) return status;
  // Room for every point at once, counted from the bytes that hold them (so
  // a message cannot make us reserve more than it carries).
  size_t room = 0;
  for (const v1::EncodedRegion& region : message.regions()) {
    room += region.x_offsets().size() / std::max<uint32_t>(region.x_offset_bytes(), 1);
  }
  const size_t first = points.ids.size();
  points.positions.reserve(points.positions.size() + room);
  points.ids.reserve(points.ids.size() + room);
  for (int r = 0; r < message.regions_size(); ++r) {
    const v1::EncodedRegion& region = message.regions(r);
    const EncodedRegionView view{
        .key = {region.i(), region.j()},
        .index_runs = {region.index_runs().data(), static_cast<size_t>(region.index_runs_size())},
        .x_offset_bytes = static_cast<int>(std::min<uint32_t>(region.x_offset_bytes(), 64)),
        .y_offset_bytes = static_cast<int>(std::min<uint32_t>(region.y_offset_bytes(), 64)),
        .x_offsets = region.x_offsets(),
        .y_offsets = region.y_offsets()};
    if (Status status = DecodeRegion(header, view, r, points); !status.ok()) {
      points.positions.resize(first);
      points.ids.resize(first);
      return status;
    }
  }
  return Status::Ok();
}

}  // namespace scallop
