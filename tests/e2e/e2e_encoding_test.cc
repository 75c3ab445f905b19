// End to end: the compact point encodings (docs/wire.md) through scallopd.
// A request that does not ask (an old client) still gets the packed arrays;
// GetPoints in one page and in many, StreamPoints and Follow asked for
// POINT_ENCODING_EXACT give the plain answer bit for bit, ids and radii
// included, for constant and radius-field worlds at the origin, at negative
// and at large coordinates; POINT_ENCODING_QUANTISED gives the same ids with
// every coordinate within S / 2^17 and the rounding; and encodings the
// server does not know, or a Follow call changing its encoding, are refused
// naming the field.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "encoded_points.h"
#include "follow_client.h"
#include "scallop/random/rng.h"
#include "tests/e2e/scallopd_process.h"
#include "tests/field_test_fields.h"
#include "tests/quantised_bound.h"
#include "tests/test_worlds.h"
#include "world_messages.h"

namespace scallop::testing {
namespace {

bool SameBits(double a, double b) {
  return std::bit_cast<uint64_t>(a) == std::bit_cast<uint64_t>(b);
}

// Points with their radii (empty for a world without a field).
struct Answer {
  PlanePoints points;
  std::vector<double> radii;
};

::testing::AssertionResult SameAnswer(const Answer& expected, const Answer& actual) {
  if (expected.points.ids != actual.points.ids) {
    return ::testing::AssertionFailure() << "ids differ (" << expected.points.ids.size() << " and "
                                         << actual.points.ids.size() << " points)";
  }
  for (size_t k = 0; k < expected.points.ids.size(); ++k) {
    if (!SameBits(expected.points.positions[k].x, actual.points.positions[k].x) ||
        !SameBits(expected.points.positions[k].y, actual.points.positions[k].y)) {
      return ::testing::AssertionFailure() << "point " << k << " differs";
    }
  }
  if (expected.radii != actual.radii) return ::testing::AssertionFailure() << "radii differ";
  return ::testing::AssertionSuccess();
}

// The same ids, and every coordinate within the quantised bound (S / 2^17,
// plus the ulps of the decoding sum).
::testing::AssertionResult WithinQuantisedBound(const Answer& expected, const Answer& actual,
                                                double side) {
  if (expected.points.ids != actual.points.ids)
    return ::testing::AssertionFailure() << "ids differ";
  for (size_t k = 0; k < expected.points.ids.size(); ++k) {
    const Vec2 a = expected.points.positions[k], b = actual.points.positions[k];
    if (std::fabs(a.x - b.x) > QuantisedBound(a.x, side) ||
        std::fabs(a.y - b.y) > QuantisedBound(a.y, side)) {
      return ::testing::AssertionFailure() << "point " << k << " beyond the bound";
    }
  }
  return ::testing::AssertionSuccess();
}

template <typename Request>
Request RequestFor(const World& world, const Rect& rect, v1::PointEncoding encoding) {
  Request request;
  *request.mutable_world() = WorldToMessage(world);
  *request.mutable_rect() = RectToMessage(rect);
  request.set_encoding(encoding);
  return request;
}

World FieldWorld() {
  WorldSpec spec{.seed = 5, .algorithm = WorldAlgorithm::kA3};
  spec.radius_field = field_test::NoiseField(5, 1.0, 3.0).spec();
  return ValidWorld(spec);
}

class E2eEncodingTest : public ::testing::Test {
 public:
  static client::ScallopClient Client() { return server_->Client(); }

 protected:
  static void SetUpTestSuite() { server_ = ScallopdProcess::Start({"--threads", "2"}).release(); }
  static void TearDownTestSuite() { delete server_; }
  void SetUp() override { ASSERT_NE(server_, nullptr); }

  // Every page, each checked to come in the encoding asked for.
  static Answer Paged(const World& world, const Rect& rect, v1::PointEncoding encoding,
                      int page_size) {
    auto request = RequestFor<v1::GetPointsRequest>(world, rect, encoding);
    request.set_page_size(page_size);
    Answer answer;
    while (true) {
      v1::GetPointsResponse page;
      const grpc::Status status = Client().GetPoints(request, page);
      EXPECT_TRUE(status.ok()) << client::DescribeStatus(status);
      EXPECT_EQ(page.points().has_encoded(), encoding != v1::POINT_ENCODING_UNSPECIFIED);
      EXPECT_TRUE(ReadPoints(page.points(), answer.points, &answer.radii).ok());
      if (!status.ok() || page.next_page_token().empty()) return answer;
      request.set_page_token(page.next_page_token());
    }
  }

  static Answer Streamed(const World& world, const Rect& rect, v1::PointEncoding encoding) {
    Answer answer;
    const grpc::Status status = Client().StreamPoints(
        RequestFor<v1::StreamPointsRequest>(world, rect, encoding),
        [&](const v1::PointsChunk& chunk) {
          EXPECT_TRUE(chunk.points().has_encoded());
          return ReadPoints(chunk.points(), answer.points, &answer.radii).ok();
        });
    EXPECT_TRUE(status.ok()) << client::DescribeStatus(status);
    return answer;
  }

  static ScallopdProcess* server_;
};
ScallopdProcess* E2eEncodingTest::server_ = nullptr;

TEST_F(E2eEncodingTest, ARequestThatDoesNotAskGetsThePackedArrays) {
  const World world = ValidWorld({.seed = 7, .algorithm = WorldAlgorithm::kA3});
  // An old client's request has no field 6: what an unset enum serialises to.
  auto request =
      RequestFor<v1::GetPointsRequest>(world, {-10, -10, 30, 30}, v1::POINT_ENCODING_UNSPECIFIED);
  v1::GetPointsRequest old_style;
  *old_style.mutable_world() = request.world();
  *old_style.mutable_rect() = request.rect();
  ASSERT_EQ(request.SerializeAsString(), old_style.SerializeAsString());
  for (v1::PointEncoding encoding : {v1::POINT_ENCODING_UNSPECIFIED, v1::POINT_ENCODING_PACKED}) {
    request.set_encoding(encoding);
    v1::GetPointsResponse response;
    ASSERT_TRUE(server_->Client().GetPoints(request, response).ok());
    EXPECT_FALSE(response.points().has_encoded());
    EXPECT_GT(response.points().xs_size(), 1000);
    EXPECT_EQ(response.points().xs_size(), response.points().ids_size());
  }
  request.set_encoding(v1::POINT_ENCODING_EXACT);
  v1::GetPointsResponse encoded;
  ASSERT_TRUE(server_->Client().GetPoints(request, encoded).ok());
  EXPECT_TRUE(encoded.points().has_encoded());
  EXPECT_EQ(encoded.points().xs_size() + encoded.points().ids_size(), 0);
}

TEST_F(E2eEncodingTest, EveryMethodEncodedEqualsThePlainAnswer) {
  constexpr uint64_t kSeed = 0xe2e23;
  Rng dice(kSeed);
  const World worlds[] = {
      ValidWorld({.seed = 7, .algorithm = WorldAlgorithm::kA3}),
      ValidWorld(
          {.seed = 11, .min_distance = 0.5, .algorithm = WorldAlgorithm::kA1, .density = 1.5}),
      FieldWorld(),
  };
  // Lower-left corners in units of d: the origin, negative, 1e9 and -1e9.
  const double anchors[][2] = {{-30, -25}, {-4e3, -9e2}, {1e9, 2e8}, {-1e9, -1e9}};
  for (const World& world : worlds) {
    const double d = world.min_distance(), side = RegionLayout(world).side();
    for (const auto& anchor : anchors) {
      const double x0 = (anchor[0] + dice.Uniform(0, 16)) * d;
      const double y0 = (anchor[1] + dice.Uniform(0, 16)) * d;
      const Rect rect{x0, y0, x0 + dice.Uniform(30, 60) * d, y0 + dice.Uniform(30, 60) * d};
      SCOPED_TRACE(world.Describe() + " rect " + std::to_string(rect.x0) + "," +
                   std::to_string(rect.y0) + " (seed " + std::to_string(kSeed) + ")");
      const Answer plain = Paged(world, rect, v1::POINT_ENCODING_UNSPECIFIED, 0);
      ASSERT_GT(plain.points.ids.size(), 100u);
      EXPECT_EQ(plain.radii.empty(), world.radius_field() == nullptr);

      EXPECT_TRUE(SameAnswer(plain, Paged(world, rect, v1::POINT_ENCODING_EXACT, 0))) << "unary";
      // A prime page size, so pages cut regions anywhere.
      EXPECT_TRUE(SameAnswer(plain, Paged(world, rect, v1::POINT_ENCODING_EXACT, 97))) << "paged";
      EXPECT_TRUE(SameAnswer(plain, Streamed(world, rect, v1::POINT_ENCODING_EXACT))) << "streamed";
      EXPECT_TRUE(
          WithinQuantisedBound(plain, Paged(world, rect, v1::POINT_ENCODING_QUANTISED, 97), side))
          << "paged";
      EXPECT_TRUE(
          WithinQuantisedBound(plain, Streamed(world, rect, v1::POINT_ENCODING_QUANTISED), side))
          << "streamed";
    }
  }
}

TEST_F(E2eEncodingTest, EncodedPagesAreSmaller) {
  const World world = ValidWorld({.seed = 7, .algorithm = WorldAlgorithm::kA3});
  const Rect rect{1e6, 1e6, 1e6 + 64, 1e6 + 64};
  size_t bytes[4] = {};
  for (v1::PointEncoding encoding :
       {v1::POINT_ENCODING_PACKED, v1::POINT_ENCODING_EXACT, v1::POINT_ENCODING_QUANTISED}) {
    v1::GetPointsResponse response;
    ASSERT_TRUE(server_->Client()
                    .GetPoints(RequestFor<v1::GetPointsRequest>(world, rect, encoding), response)
                    .ok());
    bytes[encoding] = response.points().ByteSizeLong();
  }
  // 24 bytes a point packed; 5 + 5 and about 0.02 exact; 2 + 2 and 0.02 quantised.
  EXPECT_LT(bytes[v1::POINT_ENCODING_EXACT] * 2, bytes[v1::POINT_ENCODING_PACKED]);
  EXPECT_LT(bytes[v1::POINT_ENCODING_QUANTISED] * 5, bytes[v1::POINT_ENCODING_PACKED]);
}

// The points a Follow call sent, update by update, in the order received.
std::vector<Answer> FollowPath(const World& world, v1::PointEncoding encoding,
                               const std::vector<Rect>& path) {
  std::vector<Answer> answers;
  client::FollowSession session(E2eEncodingTest::Client());
  for (size_t n = 0; n < path.size(); ++n) {
    v1::FollowRequest request;
    if (n == 0) {
      *request.mutable_world() = WorldToMessage(world);
      request.set_encoding(encoding);
    }
    *request.mutable_viewport() = RectToMessage(path[n]);
    request.set_keep_margin(4 * world.min_distance());
    Answer& answer = answers.emplace_back();
    const grpc::Status status = session.Update(request, [&](const v1::FollowResponse& response) {
      if (response.has_chunk()) {
        EXPECT_EQ(response.chunk().points().has_encoded(),
                  encoding != v1::POINT_ENCODING_UNSPECIFIED);
        EXPECT_TRUE(ReadPoints(response.chunk().points(), answer.points, &answer.radii).ok());
      }
    });
    EXPECT_TRUE(status.ok()) << client::DescribeStatus(status);
  }
  return answers;
}

TEST_F(E2eEncodingTest, FollowEncodedEqualsThePlainAnswer) {
  Rng dice(0xf011);
  for (const World& world :
       {ValidWorld({.seed = 9, .algorithm = WorldAlgorithm::kA3}), FieldWorld()}) {
    const double d = world.min_distance(), side = RegionLayout(world).side();
    // A random walk of a 40 d viewport from near -1e9, 1e9.
    std::vector<Rect> path;
    Vec2 at{-1e9 * d, 1e9 * d};
    for (int n = 0; n < 8; ++n) {
      path.push_back({at.x, at.y, at.x + 40 * d, at.y + 40 * d});
      at = at + Vec2{dice.Uniform(-12, 12) * d, dice.Uniform(-12, 12) * d};
    }
    const std::vector<Answer> plain = FollowPath(world, v1::POINT_ENCODING_UNSPECIFIED, path);
    const std::vector<Answer> exact = FollowPath(world, v1::POINT_ENCODING_EXACT, path);
    const std::vector<Answer> quantised = FollowPath(world, v1::POINT_ENCODING_QUANTISED, path);
    size_t points = 0;
    for (size_t n = 0; n < path.size(); ++n) {
      EXPECT_TRUE(SameAnswer(plain[n], exact[n])) << world.Describe() << " update " << n;
      EXPECT_TRUE(WithinQuantisedBound(plain[n], quantised[n], side))
          << world.Describe() << " update " << n;
      points += plain[n].points.ids.size();
    }
    EXPECT_GT(points, 300u) << world.Describe();
  }
}

TEST_F(E2eEncodingTest, UnknownEncodingsAndChangesAreRefusedNamingTheField) {
  const World world = ValidWorld({.seed = 7, .algorithm = WorldAlgorithm::kA3});
  const Rect rect{0, 0, 10, 10};
  const auto unknown = static_cast<v1::PointEncoding>(7);
  v1::GetPointsResponse response;
  grpc::Status status =
      server_->Client().GetPoints(RequestFor<v1::GetPointsRequest>(world, rect, unknown), response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(status.error_message().rfind("encoding: ", 0), 0u) << status.error_message();
  PlanePoints points;
  status = server_->Client().StreamAllPoints(
      RequestFor<v1::StreamPointsRequest>(world, rect, unknown), points);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(status.error_message().rfind("encoding: ", 0), 0u) << status.error_message();

  // Follow: unset or the same later is fine (PACKED is UNSPECIFIED); a change is not.
  v1::FollowRequest first;
  *first.mutable_world() = WorldToMessage(world);
  *first.mutable_viewport() = RectToMessage(rect);
  first.set_encoding(v1::POINT_ENCODING_PACKED);
  v1::FollowRequest later;
  *later.mutable_viewport() = RectToMessage({5, 5, 15, 15});
  client::FollowSession session(Client());
  const auto ignore = [](const v1::FollowResponse&) {};
  ASSERT_TRUE(session.Update(first, ignore).ok());
  ASSERT_TRUE(session.Update(later, ignore).ok());
  later.set_encoding(v1::POINT_ENCODING_UNSPECIFIED);
  ASSERT_TRUE(session.Update(later, ignore).ok());
  later.set_encoding(v1::POINT_ENCODING_QUANTISED);
  status = session.Update(later, ignore);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(status.error_message().rfind("encoding: ", 0), 0u) << status.error_message();

  client::FollowSession bad_first(Client());
  first.set_encoding(unknown);
  status = bad_first.Update(first, ignore);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(status.error_message().rfind("encoding: ", 0), 0u) << status.error_message();
}

}  // namespace
}  // namespace scallop::testing
