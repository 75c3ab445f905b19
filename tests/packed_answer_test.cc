// GetPoints' packed answer written by hand (server/packed_answer.h) against
// protobuf's own serialization of the same message: the same bytes for any
// number of points (each size of the arrays' varint lengths), edge doubles,
// with and without a page token, whatever room the writer was given beyond
// its points, in bulk as one by one; and planted faults the checks catch.
#include "server/packed_answer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "scallop/plane/plane_engine.h"
#include "scallop/random/rng.h"
#include "world_messages.h"

namespace scallop::server {
namespace {

std::string Bytes(const grpc::ByteBuffer& buffer) {
  std::vector<grpc::Slice> slices;
  EXPECT_TRUE(buffer.Dump(&slices).ok());
  std::string bytes;
  for (const grpc::Slice& slice : slices) {
    bytes.append(reinterpret_cast<const char*>(slice.begin()), slice.size());
  }
  return bytes;
}

// Doubles whose bits a careless copy could change: signed zero, subnormals, extremes.
constexpr double kEdgeDoubles[] = {-0.0,
                                   0.0,
                                   std::numeric_limits<double>::denorm_min(),
                                   -std::numeric_limits<double>::denorm_min(),
                                   std::numeric_limits<double>::max(),
                                   std::numeric_limits<double>::lowest(),
                                   0x1.0p32,
                                   -0x1.fffffffffffffp31};

struct Answer {
  std::string written;   // by PackedAnswerWriter
  std::string expected;  // by protobuf, of the same GetPointsResponse
};

// `count` random points (edge doubles first) of seed `seed`, written both ways;
// with `plant`, the writer's last point has one bit of x flipped.
Answer WriteBothWays(uint64_t seed, size_t count, size_t spare, const std::string& token,
                     const std::string& world, bool plant = false) {
  Rng rng(seed);
  PackedAnswerWriter writer(count + spare);
  v1::GetPointsResponse response;
  v1::Points& points = *response.mutable_points();
  for (size_t k = 0; k < count; ++k) {
    constexpr size_t kEdges = std::size(kEdgeDoubles);
    const Vec2 position{k < kEdges ? kEdgeDoubles[k] : rng.Uniform(-1e9, 1e9),
                        k < kEdges ? kEdgeDoubles[kEdges - 1 - k] : rng.Uniform(-1e-3, 1e-3)};
    const uint64_t id = rng.NextBits();
    points.add_xs(position.x);
    points.add_ys(position.y);
    points.add_ids(id);
    Vec2 written = position;
    if (plant && k + 1 == count) written.x = std::nextafter(written.x, INFINITY);
    writer.Append(written, id);
  }
  EXPECT_EQ(writer.count(), count);
  response.set_next_page_token(token);
  EXPECT_TRUE(response.mutable_world()->ParseFromString(world));
  return {Bytes(writer.Finish(token, world)), response.SerializeAsString()};
}

TEST(PackedAnswerTest, WritesTheBytesProtobufWrites) {
  const std::string world =
      WorldToMessage(*World::Create({.seed = 7, .min_distance = 0.5})).SerializeAsString();
  // 8 n bytes an array: none (no field), then 1-, 2- and 3-byte varint lengths.
  for (const size_t count : {size_t{0}, size_t{1}, size_t{3}, size_t{15}, size_t{16}, size_t{1000},
                             size_t{2047}, size_t{2048}, size_t{20000}}) {
    for (const size_t spare : {size_t{0}, size_t{5}}) {
      // No token, a one-byte length, a two-byte length.
      for (const size_t token_size : {size_t{0}, size_t{40}, size_t{200}}) {
        const uint64_t seed = 1000 * count + 10 * spare + token_size;
        SCOPED_TRACE("seed " + std::to_string(seed) + ", " + std::to_string(count) + " points");
        const Answer answer =
            WriteBothWays(seed, count, spare, std::string(token_size, 't'), world);
        EXPECT_EQ(answer.written, answer.expected);
        v1::GetPointsResponse parsed;
        ASSERT_TRUE(parsed.ParseFromString(answer.written));
        EXPECT_TRUE(parsed.has_points());
        EXPECT_EQ(parsed.points().ids_size(), static_cast<int>(count));
      }
    }
  }
}

// AppendRun (a region's points in bulk) against the same points appended one
// by one: runs of every length up to 9 (odd and even, for its two-at-a-time
// copy) and longer, at every offset in the writer, in random chunks.
TEST(PackedAnswerTest, RunsWriteWhatPointsOneByOneWrite) {
  const std::string world = WorldToMessage(*World::Create({.seed = 7})).SerializeAsString();
  for (const uint64_t seed : {1, 2, 3, 4, 5, 11, 12, 13, 14, 15}) {
    // Both loops, whatever the CPU: the fastest it has, and two lanes.
    const CopyLanes lanes = seed > 10 ? CopyLanes::kTwoLanes : CopyLanes::kFastest;
    SCOPED_TRACE("seed " + std::to_string(seed));
    Rng rng(seed);
    std::vector<Vec2> points(1000);
    for (Vec2& p : points) p = {rng.Uniform(-1e6, 1e6), rng.Uniform(-1e6, 1e6)};
    PackedAnswerWriter one_by_one(points.size());
    PackedAnswerWriter in_runs(points.size(), lanes);
    uint64_t next_id = rng.NextBits() >> 1;
    for (size_t start = 0; start < points.size();) {
      const size_t count =
          std::min(points.size() - start, rng.Below(4) == 0 ? 50 + rng.Below(200) : rng.Below(10));
      for (size_t k = 0; k < count; ++k) one_by_one.Append(points[start + k], next_id + k);
      in_runs.AppendRun(points.data() + start, count, next_id);
      start += count;
      next_id += count + rng.Below(3);  // a new region: ids jump
    }
    EXPECT_EQ(in_runs.count(), points.size());
    EXPECT_EQ(Bytes(in_runs.Finish("", world)), Bytes(one_by_one.Finish("", world)));
  }
  // Planted: a run whose ids start one off.
  for (const CopyLanes lanes : {CopyLanes::kFastest, CopyLanes::kTwoLanes}) {
    PackedAnswerWriter one_by_one(5);
    PackedAnswerWriter in_runs(5, lanes);
    const Vec2 points[5] = {{1, 2}, {3, 4}, {5, 6}, {7, 8}, {9, 10}};
    for (uint64_t k = 0; k < 5; ++k) one_by_one.Append(points[k], 10 + k);
    in_runs.AppendRun(points, 5, 11);
    EXPECT_NE(Bytes(in_runs.Finish("", world)), Bytes(one_by_one.Finish("", world)));
  }
}

// AppendInside (a cut region's points filtered in bulk) against the points
// inside appended one by one: regions of every size up to 9 (odd and even,
// for its two-at-a-time pass) and larger, cut on every set of sides (the
// sides CuttingSides gives for the region's rectangle), with points on the
// rectangle's edges (x0 and y0 kept, x1 and y1 not: half-open), at every
// offset in the writer.
TEST(PackedAnswerTest, CutRegionsWriteWhatTheirPointsInsideWrite) {
  const std::string world = WorldToMessage(*World::Create({.seed = 7})).SerializeAsString();
  int sides_seen = 0;
  for (const uint64_t seed : {1, 2, 3, 4, 5, 6, 7, 8, 11, 12, 13, 14, 15, 16, 17, 18}) {
    // Both loops, whatever the CPU: the fastest it has, and two lanes.
    const CopyLanes lanes = seed > 10 ? CopyLanes::kTwoLanes : CopyLanes::kFastest;
    SCOPED_TRACE("seed " + std::to_string(seed));
    Rng rng(seed);
    PackedAnswerWriter one_by_one(20000);
    PackedAnswerWriter in_bulk(20000, lanes);
    uint64_t next_id = rng.NextBits() >> 1;
    for (int region = 0; region < 200; ++region) {
      // A region owning [0, 16)^2, cut by a rectangle whose sides fall inside it or beyond.
      const Rect owned{0, 0, 16, 16};
      auto edge = [&](double beyond) { return rng.Below(2) == 0 ? beyond : rng.Uniform(1, 15); };
      Rect rect{edge(-5), edge(-5), edge(21), edge(21)};
      if (rect.x1 <= rect.x0) std::swap(rect.x0, rect.x1);
      if (rect.y1 <= rect.y0) std::swap(rect.y0, rect.y1);
      const int sides = CuttingSides(rect, owned);
      sides_seen |= 1 << sides;
      const size_t count = rng.Below(4) == 0 ? 100 + rng.Below(300) : rng.Below(10);
      std::vector<Vec2> points(count);
      for (Vec2& p : points) {
        p = {rng.Uniform(0, 16), rng.Uniform(0, 16)};
        // Now and then exactly on an edge of the rectangle that crosses the region.
        auto on_edge = [&](double& coordinate, double low, double high) {
          const double edge = rng.Below(2) == 0 ? low : high;
          if (rng.Below(8) == 0 && 0 <= edge && edge < 16) coordinate = edge;
        };
        on_edge(p.x, rect.x0, rect.x1);
        on_edge(p.y, rect.y0, rect.y1);
      }
      size_t inside = 0;
      for (size_t k = 0; k < count; ++k) {
        if (rect.Contains(points[k])) {
          one_by_one.Append(points[k], next_id + k);
          ++inside;
        }
      }
      EXPECT_EQ(in_bulk.AppendInside(points.data(), count, next_id, rect, sides), inside);
      next_id += count + rng.Below(3);  // a new region: ids jump
    }
    EXPECT_EQ(in_bulk.count(), one_by_one.count());
    EXPECT_EQ(Bytes(in_bulk.Finish("", world)), Bytes(one_by_one.Finish("", world)));
  }
  EXPECT_EQ(sides_seen, 0xFFFF) << "every set of cutting sides";
  // Planted: a side that cuts left untested keeps a point beyond it.
  for (const CopyLanes lanes : {CopyLanes::kFastest, CopyLanes::kTwoLanes}) {
    PackedAnswerWriter one_by_one(6);
    PackedAnswerWriter in_bulk(6, lanes);
    const Vec2 points[5] = {{1, 2}, {3, 4}, {5, 6}, {7, 8}, {9, 10}};
    const Rect rect{2, 0, 10, 10};  // cuts x0 only
    for (uint64_t k = 1; k < 5; ++k) one_by_one.Append(points[k], 10 + k);
    EXPECT_EQ(in_bulk.AppendInside(points, 5, 10, rect, /*sides=*/0), 5u);
    EXPECT_NE(Bytes(in_bulk.Finish("", world)), Bytes(one_by_one.Finish("", world)));
  }
}

// A writer with just the room its calls require (a run's points, all of a
// cut region's), filled by a run and then a cut region of every size up to
// 13 in both loops: the loops' stores beyond the points kept stay inside the
// writer's buffer (AddressSanitizer checks that in its build) and leave the
// points written intact.
TEST(PackedAnswerTest, FourLaneLoopsStayInTheirRoom) {
  const std::string world = WorldToMessage(*World::Create({.seed = 7})).SerializeAsString();
  Rng rng(21);
  for (const CopyLanes lanes : {CopyLanes::kFastest, CopyLanes::kTwoLanes}) {
    for (size_t count = 0; count <= 13; ++count) {
      std::vector<Vec2> points(count);
      for (Vec2& p : points) p = {rng.Uniform(0, 16), rng.Uniform(0, 16)};
      const Rect rect{rng.Uniform(0, 8), 0, 16, 16};
      size_t inside = 0;
      for (const Vec2& p : points) inside += rect.Contains(p) ? 1 : 0;
      // The run first, then the cut region, whose loop's stores go furthest beyond its points.
      PackedAnswerWriter one_by_one(2 * count);
      for (size_t k = 0; k < count; ++k) one_by_one.Append(points[k], 200 + k);
      for (size_t k = 0; k < count; ++k) {
        if (rect.Contains(points[k])) one_by_one.Append(points[k], 100 + k);
      }
      PackedAnswerWriter tight(2 * count, lanes);
      tight.AppendRun(points.data(), count, 200);
      EXPECT_EQ(
          tight.AppendInside(points.data(), count, 100, rect, CuttingSides(rect, {0, 0, 16, 16})),
          inside);
      EXPECT_EQ(Bytes(tight.Finish("", world)), Bytes(one_by_one.Finish("", world)))
          << count << " points";
    }
  }
}

TEST(PackedAnswerTest, AnEmptyWorldMessageIsStillWritten) {
  // A world of all defaults serializes to nothing; the field is present all the same.
  const Answer answer = WriteBothWays(3, 4, 0, "", "");
  EXPECT_EQ(answer.written, answer.expected);
}

TEST(PackedAnswerTest, CatchesAPlantedFault) {
  const std::string world = WorldToMessage(*World::Create({.seed = 7})).SerializeAsString();
  for (const size_t count : {size_t{1}, size_t{20000}}) {
    const Answer answer = WriteBothWays(count, count, 0, "", world, /*plant=*/true);
    EXPECT_NE(answer.written, answer.expected) << count << " points";
    EXPECT_EQ(answer.written.size(), answer.expected.size());
  }
}

}  // namespace
}  // namespace scallop::server
