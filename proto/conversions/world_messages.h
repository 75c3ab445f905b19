// Conversions between the API's messages (scallop.v1.World, Rect, Points) and
// the core's value types, shared by scallopd and the client library so both
// read the proto's defaults (density 0, generator_version 0) the same way.
#pragma once

#include <span>

#include "scallop/base/status.h"
#include "scallop/geometry/rect.h"
#include "scallop/plane/plane_engine.h"
#include "scallop/plane/world.h"
#include "scallop/v1/scallop.pb.h"

namespace scallop {

// The message's world, with its zero defaults filled in, validated
// (World::Create). INVALID_ARGUMENT naming the field (world.algorithm,
// world.density, world.min_distance, world.generator_version) otherwise.
StatusOr<World> WorldFromMessage(const v1::World& message);

// The world as a message, every field explicit (no zero defaults left).
v1::World WorldToMessage(const World& world);
// A spec as a message, field for field, valid or not: what a client sends
// for the server to judge.
v1::World WorldToMessage(const WorldSpec& spec);

// Field-for-field; the range checks are CheckQueryRect's (query_rect.h).
Rect RectFromMessage(const v1::Rect& message);
v1::Rect RectToMessage(const Rect& rect);

// Points [begin, end) of `points` appended to the packed arrays of `message`.
void AppendPoints(const PlanePoints& points, size_t begin, size_t end, v1::Points& message);

// Appends points to the packed arrays of a message through plain pointers:
// room for `capacity` points is made up front, and the destructor cuts the
// arrays to the points appended. (add_xs() and the like check the capacity
// and store the size for every element, three times a point; that copy was
// 15% of a warm server's time.) Use the message only after the appender is
// gone. REQUIRES: at most `capacity` calls of Append.
class PointsAppender {
 public:
  PointsAppender(v1::Points& message, size_t capacity);
  ~PointsAppender();
  PointsAppender(const PointsAppender&) = delete;
  PointsAppender& operator=(const PointsAppender&) = delete;

  void Append(Vec2 position, uint64_t id) {
    xs_[count_] = position.x;
    ys_[count_] = position.y;
    ids_[count_] = id;
    ++count_;
  }
  size_t count() const { return count_; }

 private:
  v1::Points& message_;
  int start_;  // the arrays' size before
  double* xs_;
  double* ys_;
  uint64_t* ids_;
  size_t count_ = 0;
};

// The message's points appended to `points`. INVALID_ARGUMENT when the three
// arrays differ in length (a malformed message).
Status ReadPoints(const v1::Points& message, PlanePoints& points);

}  // namespace scallop
