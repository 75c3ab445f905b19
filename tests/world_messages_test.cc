// The API's point arrays as scallopd fills them: PointsAppender writes
// through plain pointers into room made up front, so its sizes and contents
// are checked against add_xs()-style appends, on empty and non-empty
// messages, with the room used in full, in part and not at all.
#include "world_messages.h"

#include <gtest/gtest.h>

#include <vector>

namespace scallop {
namespace {

// The message's points, read back as plain values.
PlanePoints Read(const v1::Points& message) {
  PlanePoints points;
  EXPECT_TRUE(ReadPoints(message, points).ok());
  return points;
}

PlanePoints Sample(size_t count, double shift) {
  PlanePoints points;
  for (size_t k = 0; k < count; ++k) {
    points.positions.push_back(
        {shift + 0.5 * static_cast<double>(k), shift - static_cast<double>(k)});
    points.ids.push_back(1000 + k);
  }
  return points;
}

void ExpectSame(const PlanePoints& a, const PlanePoints& b) {
  ASSERT_EQ(a.ids.size(), b.ids.size());
  for (size_t k = 0; k < a.ids.size(); ++k) {
    EXPECT_EQ(a.positions[k], b.positions[k]) << k;
    EXPECT_EQ(a.ids[k], b.ids[k]) << k;
  }
}

TEST(PointsAppenderTest, AppendsWhatWasGivenAndCutsTheRestOfTheRoom) {
  const PlanePoints earlier = Sample(2, -7.25), later = Sample(5, 3.0);
  for (size_t existing : {size_t{0}, size_t{2}}) {
    for (size_t appended : {size_t{0}, size_t{3}, size_t{5}}) {
      v1::Points message;
      PlanePoints expected;
      for (size_t k = 0; k < existing; ++k) {
        message.add_xs(earlier.positions[k].x);
        message.add_ys(earlier.positions[k].y);
        message.add_ids(earlier.ids[k]);
        expected.positions.push_back(earlier.positions[k]);
        expected.ids.push_back(earlier.ids[k]);
      }
      {
        PointsAppender appender(message, 5);
        for (size_t k = 0; k < appended; ++k) appender.Append(later.positions[k], later.ids[k]);
        EXPECT_EQ(appender.count(), appended);
      }
      for (size_t k = 0; k < appended; ++k) {
        expected.positions.push_back(later.positions[k]);
        expected.ids.push_back(later.ids[k]);
      }
      ASSERT_EQ(message.xs_size(), static_cast<int>(existing + appended));
      ASSERT_EQ(message.ys_size(), message.xs_size());
      ASSERT_EQ(message.ids_size(), message.xs_size());
      ExpectSame(Read(message), expected);
    }
  }
}

TEST(PointsAppenderTest, AppendPointsCopiesTheRange) {
  const PlanePoints points = Sample(6, 1.5);
  v1::Points message;
  AppendPoints(points, 1, 4, message);
  AppendPoints(points, 5, 6, message);
  AppendPoints(points, 2, 2, message);  // empty range
  PlanePoints expected;
  for (size_t k : {1, 2, 3, 5}) {
    expected.positions.push_back(points.positions[k]);
    expected.ids.push_back(points.ids[k]);
  }
  ExpectSame(Read(message), expected);
}

}  // namespace
}  // namespace scallop
