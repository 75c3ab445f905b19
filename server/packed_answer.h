// GetPoints' common answer (packed arrays, neither radii nor layers) written as
// wire bytes straight into the slices gRPC sends: the points are copied once,
// from the cached regions, instead of into a GetPointsResponse's arrays and
// again by its serialization. The bytes are those protobuf writes for the
// same message (tests/packed_answer_test.cc), so no client sees a difference.
#pragma once

#include <grpcpp/support/byte_buffer.h>
#include <grpcpp/support/slice.h>

#include <bit>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "scallop/geometry/rect.h"
#include "scallop/geometry/vec2.h"

namespace scallop::server {

// Packed doubles and fixed64 are little-endian on the wire, as in memory here.
static_assert(std::endian::native == std::endian::little, "packed_answer.h copies raw words");

// The loops AppendRun and AppendInside run: four points at a time in AVX2
// where the CPU has it (kFastest), else two in SSE2 (kTwoLanes); both write
// the same bytes (tests/packed_answer_test.cc compares them).
enum class CopyLanes { kFastest, kTwoLanes };

// The appender WritePoints' callers fill (encoded_points.h): Append and StartLayer.
// Not thread-safe; one answer per writer.
class PackedAnswerWriter {
 public:
  // Room for `capacity` points: one allocation of 24 bytes a point.
  explicit PackedAnswerWriter(size_t capacity, CopyLanes lanes = CopyLanes::kFastest);

  // REQUIRES: fewer than `capacity` points appended so far.
  void Append(Vec2 position, uint64_t id) {
    xs_[count_] = position.x;
    ys_[count_] = position.y;
    ids_[count_] = id;
    ++count_;
  }
  // points[0, count) with ids first_id + k, as `count` Appends would.
  // REQUIRES: room for them.
  void AppendRun(const Vec2* points, size_t count, uint64_t first_id);
  // Those of points[0, count) (ids first_id + k) that lie in `rect`, in
  // order, as Appends would; returns how many. `sides` (CuttingSides of the
  // region's rectangle) are the sides of `rect` that may leave a point out:
  // only those are tested. One pass without a branch on the points: each is
  // written where the next kept point goes, and the count moves past it only
  // if it is inside. REQUIRES: room for all `count`.
  size_t AppendInside(const Vec2* points, size_t count, uint64_t first_id, const Rect& rect,
                      int sides);
  // The packed answer of a world without layers: nothing to record.
  void StartLayer(int /*layer*/) {}
  size_t count() const { return count_; }

  // The serialized GetPointsResponse {points {xs, ys, ids}, next_page_token,
  // world} of the points appended, `world_message` being the serialized
  // v1::World. The points' bytes are shared with the buffer, not copied.
  grpc::ByteBuffer Finish(std::string_view next_page_token, std::string_view world_message) const;

 private:
  size_t capacity_;
  grpc::Slice data_;  // xs, then ys, then ids, `capacity_` of each
  double* xs_;
  double* ys_;
  uint64_t* ids_;
  // Not size_t, for the reason PointsAppender gives (world_messages.h): a
  // store to ids_ could alias it, and the copy would reload it a point.
  uint32_t count_ = 0;
  bool four_lanes_;
};

// What VisitPoints calls for an appender (WritePoints' or this writer): its
// Append a point, and when it has them its AppendRun for the points of a
// region wholly inside and its AppendInside for those of a region the
// rectangle cuts, in bulk.
template <typename Appender>
struct AppendTo {
  Appender& appender;
  void operator()(const Vec2& position, uint64_t id) const { appender.Append(position, id); }
  void operator()(const Vec2* points, size_t count, uint64_t first_id) const requires requires {
    appender.AppendRun(points, count, first_id);
  }
  { appender.AppendRun(points, count, first_id); }
  size_t operator()(const Vec2* points, size_t count, uint64_t first_id, const Rect& rect,
                    int sides) const requires requires {
    appender.AppendInside(points, count, first_id, rect, sides);
  }
  { return appender.AppendInside(points, count, first_id, rect, sides); }
};

}  // namespace scallop::server
