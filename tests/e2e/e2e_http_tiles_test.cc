// End to end (issue 21): scallopd's HTTP tiles against its own gRPC answers.
// A JSON tile holds exactly GetPoints' points of the tile's rectangle (ids and
// coordinates to the bit), the binary tile the same as the JSON one (read by
// a decoder written from docs/tiles.md), the PNG decodes and is dark at every
// point; ETags are stable and If-None-Match gets 304; bad paths, unknown
// worlds, out-of-range tiles, the area limit, load shedding and tokens get
// their documented HTTP codes. A radius-field world's tiles carry each
// point's R (JSON "rs", binary flag bit 0 and its array), equal to
// GetPoints' radii, and its PNG draws disks of R/4. A layered world's tiles
// carry each point's layer and spacing as GetPoints does, with ETags of
// format version 4 while a plain world's stay version 3, and a colour PNG.
#include <gtest/gtest.h>
#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <nlohmann/json.hpp>

#include "scallop/random/rng.h"
#include "tests/e2e/metrics_scrape.h"
#include "tests/e2e/scallopd_process.h"
#include "world_messages.h"

namespace scallop::testing {
namespace {

namespace http = boost::beast::http;
using std::chrono::seconds;

// A tile's points as a format carries them.
struct TilePointsRead {
  std::vector<uint64_t> ids;
  std::vector<double> xs;
  std::vector<double> ys;
  std::array<double, 4> rect{};
};

// The address line scallopd prints for --http-listen.
std::string HttpAddress(const ScallopdProcess& server) {
  for (int line = 0; line < 3; ++line) {
    const std::string text = server.ReadStdoutLine(seconds(10));
    if (text.starts_with("scallopd http on ")) return text.substr(text.rfind(' ') + 1);
  }
  return {};
}

TilePointsRead ReadJsonTile(const std::string& body) {
  const nlohmann::json json = nlohmann::json::parse(body);
  TilePointsRead tile;
  for (const auto& id : json.at("ids")) tile.ids.push_back(std::stoull(id.get<std::string>()));
  tile.xs = json.at("xs").get<std::vector<double>>();
  tile.ys = json.at("ys").get<std::vector<double>>();
  for (int k = 0; k < 4; ++k) tile.rect[k] = json.at("rect")[k].get<double>();
  return tile;
}

// docs/tiles.md, "Binary": little-endian, an 80-byte header, then the arrays.
uint64_t ReadLittleEndian(const std::string& bytes, size_t offset, int size) {
  uint64_t value = 0;
  for (int byte = size - 1; byte >= 0; --byte) {
    value = value << 8 | static_cast<unsigned char>(bytes.at(offset + byte));
  }
  return value;
}
double ReadDouble(const std::string& bytes, size_t offset) {
  const uint64_t bits = ReadLittleEndian(bytes, offset, 8);
  double value = 0;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}
TilePointsRead ReadBinaryTile(const std::string& bytes) {
  TilePointsRead tile;
  EXPECT_EQ(bytes.substr(0, 4), "SCTL");
  EXPECT_EQ(ReadLittleEndian(bytes, 4, 2), 1u);  // layout version
  EXPECT_EQ(ReadLittleEndian(bytes, 6, 2), 0u);  // no rs, no layers
  const size_t count = ReadLittleEndian(bytes, 8, 4);
  EXPECT_EQ(bytes.size(), 80 + 24 * count);
  for (int k = 0; k < 4; ++k) tile.rect[k] = ReadDouble(bytes, 48 + 8 * k);
  for (size_t k = 0; k < count; ++k) {
    tile.ids.push_back(ReadLittleEndian(bytes, 80 + 8 * k, 8));
    tile.xs.push_back(ReadDouble(bytes, 80 + 8 * count + 8 * k));
    tile.ys.push_back(ReadDouble(bytes, 80 + 16 * count + 8 * k));
  }
  return tile;
}

// Grey pixels of a PNG, row 0 at the top; empty if it does not decode.
std::vector<uint8_t> DecodeGreyPng(const std::string& bytes, int& width, int& height) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size())) return {};
  image.format = PNG_FORMAT_GRAY;
  std::vector<uint8_t> pixels(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr)) return {};
  width = static_cast<int>(image.width);
  height = static_cast<int>(image.height);
  return pixels;
}

class E2eHttpTilesTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    server_ = ScallopdProcess::Start({"--http-listen", "127.0.0.1:0", "--world", "coast:7:1:a3",
                                      "--world", "dense:9:0.5:a1:1.5"})
                  .release();
    ASSERT_NE(server_, nullptr);
    http_ = HttpAddress(*server_);
    ASSERT_FALSE(http_.empty()) << server_->Log();
  }
  static void TearDownTestSuite() { delete server_; }

  static HttpAnswer Get(const std::string& target,
                        const std::map<std::string, std::string>& headers = {}) {
    return Fetch(http_, http::verb::get, target, headers);
  }

  // GetPoints of the tile's rectangle, every page.
  static PlanePoints PointsByGrpc(const std::string& world, const std::array<double, 4>& rect) {
    v1::GetPointsRequest request;
    request.set_world_name(world);
    *request.mutable_rect() = RectToMessage({rect[0], rect[1], rect[2], rect[3]});
    request.set_page_size(1000);  // several pages for the larger tiles
    PlanePoints points;
    const grpc::Status status = server_->Client().GetAllPoints(request, points);
    EXPECT_TRUE(status.ok()) << status.error_message();
    return points;
  }

  static ScallopdProcess* server_;
  static std::string http_;
};
ScallopdProcess* E2eHttpTilesTest::server_ = nullptr;
std::string E2eHttpTilesTest::http_;

// Random tiles of both worlds at levels 0 to 2, near the origin, at negative
// indices and at the edge of the precision range, JSON against GetPoints.
TEST_F(E2eHttpTilesTest, JsonAndBinaryTilesEqualGetPointsOfTheirRectangle) {
  constexpr uint64_t kSeed = 21;
  SCOPED_TRACE("seed " + std::to_string(kSeed));
  Rng rng(kSeed);
  int checked = 0;
  for (const std::string world : {"coast", "dense"}) {
    for (int trial = 0; trial < 8; ++trial) {
      const int level = static_cast<int>(rng.Below(3));
      const int64_t half = int64_t{1} << (28 - level);
      int64_t i = static_cast<int64_t>(rng.Below(40)) - 20;
      int64_t j = static_cast<int64_t>(rng.Below(40)) - 20;
      if (trial == 0) i = half - 1, j = -half;  // the corners of the precision range
      const std::string target = "/v1/worlds/" + world + "/tiles/" + std::to_string(i) + "/" +
                                 std::to_string(j) + "?level=" + std::to_string(level);
      SCOPED_TRACE(target);
      const HttpAnswer json = Get(target + "&format=json");
      ASSERT_EQ(json.status, 200) << json.body;
      EXPECT_EQ(json.content_type, "application/json");
      const TilePointsRead tile = ReadJsonTile(json.body);
      // The rectangle is the regions' own: region side 16 d at level 0.
      const double d = world == "coast" ? 1.0 : 0.5;
      const double side = 16 * d * std::ldexp(1.0, level);
      EXPECT_EQ(tile.rect[0], static_cast<double>(i) * side);
      EXPECT_EQ(tile.rect[3], static_cast<double>(j + 1) * side);
      const PlanePoints expected = PointsByGrpc(world, tile.rect);
      ASSERT_GT(expected.ids.size(), 100u);
      EXPECT_EQ(tile.ids, expected.ids);
      ASSERT_EQ(tile.xs.size(), expected.positions.size());
      for (size_t k = 0; k < tile.xs.size(); ++k) {
        // Bit for bit: == on doubles, and the text read back exactly.
        ASSERT_EQ(tile.xs[k], expected.positions[k].x) << k;
        ASSERT_EQ(tile.ys[k], expected.positions[k].y) << k;
      }
      const HttpAnswer binary = Get(target + "&format=bin");
      ASSERT_EQ(binary.status, 200);
      EXPECT_EQ(binary.content_type, "application/vnd.scallop.tile");
      const TilePointsRead decoded = ReadBinaryTile(binary.body);
      EXPECT_EQ(decoded.ids, tile.ids);
      EXPECT_EQ(decoded.xs, tile.xs);
      EXPECT_EQ(decoded.ys, tile.ys);
      EXPECT_EQ(decoded.rect, tile.rect);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 16);
}

// The format from the extension, from format=, or from Accept (then with
// "Vary: Accept"); all three give the same bytes for the same format.
TEST_F(E2eHttpTilesTest, FormatComesFromExtensionParameterOrAccept) {
  const HttpAnswer by_extension = Get("/v1/worlds/coast/tiles/3/-4.bin");
  const HttpAnswer by_parameter = Get("/v1/worlds/coast/tiles/3/-4?format=bin");
  const HttpAnswer by_accept =
      Get("/v1/worlds/coast/tiles/3/-4", {{"Accept", "application/vnd.scallop.tile"}});
  ASSERT_EQ(by_extension.status, 200);
  EXPECT_EQ(by_parameter.body, by_extension.body);
  EXPECT_EQ(by_accept.body, by_extension.body);
  EXPECT_EQ(by_extension.headers.count("vary"), 0u);
  EXPECT_EQ(by_accept.headers.at("vary"), "Accept");
  EXPECT_EQ(Get("/v1/worlds/coast/tiles/3/-4").content_type, "application/json");
  EXPECT_EQ(Get("/v1/worlds/coast/tiles/3/-4.png?format=json").status, 400);  // disagree
}

// Every point's pixel is dark, and a pixel farther than its reach from every
// point is white: the PNG draws the tile's points and nothing else.
TEST_F(E2eHttpTilesTest, PngTileDecodesAndShowsTheTilesPoints) {
  const HttpAnswer png = Get("/v1/worlds/coast/tiles/-2/1.png?level=1");
  ASSERT_EQ(png.status, 200);
  EXPECT_EQ(png.content_type, "image/png");
  int width = 0, height = 0;
  const std::vector<uint8_t> pixels = DecodeGreyPng(png.body, width, height);
  ASSERT_EQ(width, 256);
  ASSERT_EQ(height, 256);
  const TilePointsRead tile = ReadJsonTile(Get("/v1/worlds/coast/tiles/-2/1?level=1").body);
  const double pixel = (tile.rect[2] - tile.rect[0]) / 256;
  for (size_t k = 0; k < tile.xs.size(); ++k) {
    const int column = static_cast<int>((tile.xs[k] - tile.rect[0]) / pixel);
    const int row = static_cast<int>((tile.rect[3] - tile.ys[k]) / pixel);
    ASSERT_LT(pixels[row * 256 + column], 128) << "point " << tile.ids[k] << " not drawn";
  }
  // Points beyond the tile come from GetPoints of a margin around it.
  const PlanePoints around = PointsByGrpc(
      "coast", {tile.rect[0] - 2, tile.rect[1] - 2, tile.rect[2] + 2, tile.rect[3] + 2});
  int white = 0, dark = 0;
  for (int row = 0; row < 256; ++row) {
    for (int column = 0; column < 256; ++column) {
      const double x = tile.rect[0] + (column + 0.5) * pixel;
      const double y = tile.rect[3] - (row + 0.5) * pixel;
      double nearest = 1e9;
      for (const Vec2& p : around.positions)
        nearest = std::min(nearest, std::hypot(p.x - x, p.y - y));
      const bool must_be_white = nearest > 0.25 + pixel;  // radius d/4, and a pixel
      if (must_be_white) {
        ++white;
        ASSERT_EQ(pixels[row * 256 + column], 255) << "row " << row << " column " << column;
      }
      dark += pixels[row * 256 + column] < 128;
    }
  }
  EXPECT_GT(white, 256 * 256 / 2);
  EXPECT_GT(dark, static_cast<int>(tile.xs.size()));
}

TEST_F(E2eHttpTilesTest, StrongEtagsAndIfNoneMatchGiveNotModified) {
  const std::string target = "/v1/worlds/coast/tiles/5/6.json";
  const HttpAnswer first = Get(target);
  ASSERT_EQ(first.status, 200);
  const std::string etag = first.headers.at("etag");
  EXPECT_TRUE(etag.starts_with("\"") && etag.ends_with("\"")) << etag;  // strong: no W/
  EXPECT_EQ(first.headers.at("cache-control"), "public, max-age=31536000, immutable");
  EXPECT_EQ(Get(target).headers.at("etag"), etag);
  const HttpAnswer again = Get(target, {{"If-None-Match", etag}});
  EXPECT_EQ(again.status, 304);
  EXPECT_TRUE(again.body.empty());
  EXPECT_EQ(again.headers.at("etag"), etag);
  EXPECT_EQ(Get(target, {{"If-None-Match", "\"other\", " + etag}}).status, 304);
  EXPECT_EQ(Get(target, {{"If-None-Match", "\"other\""}}).status, 200);
  // Another tile, format, level or world: another ETag.
  std::set<std::string> etags{etag};
  for (const std::string other :
       {"/v1/worlds/coast/tiles/5/7.json", "/v1/worlds/coast/tiles/6/6.json",
        "/v1/worlds/coast/tiles/5/6.bin", "/v1/worlds/coast/tiles/5/6.png",
        "/v1/worlds/coast/tiles/5/6.json?level=1", "/v1/worlds/dense/tiles/5/6.json",
        "/v1/worlds/default/tiles/5/6.json"}) {
    const HttpAnswer answer = Get(other);
    ASSERT_EQ(answer.status, 200) << other;
    EXPECT_TRUE(etags.insert(answer.headers.at("etag")).second) << other;
  }
}

// Planted bad requests: each must get its code, a JSON message and no-store.
TEST_F(E2eHttpTilesTest, BadPathsAndParametersGet400UnknownWorlds404) {
  const std::vector<std::pair<std::string, int>> cases = {
      {"/v1/worlds/coast/tiles/0", 400},
      {"/v1/worlds/coast/tiles/0/0/0", 400},
      {"/v1/worlds//tiles/0/0", 400},
      {"/v1/worlds/coast/tile/0/0", 404},
      {"/v1/worlds/coast/tiles/nan/0", 400},
      {"/v1/worlds/coast/tiles/inf/0", 400},
      {"/v1/worlds/coast/tiles/-inf/0", 400},
      {"/v1/worlds/coast/tiles/1e3/0", 400},
      {"/v1/worlds/coast/tiles/0x10/0", 400},
      {"/v1/worlds/coast/tiles/1.5/0", 400},
      {"/v1/worlds/coast/tiles/+1/0", 400},
      {"/v1/worlds/coast/tiles/01/0", 400},
      {"/v1/worlds/coast/tiles/-0/0", 400},
      {"/v1/worlds/coast/tiles/%201/0", 400},
      {"/v1/worlds/coast/tiles/0/0.gif", 400},
      {"/v1/worlds/coast/tiles/0/0?level=-1", 400},
      {"/v1/worlds/coast/tiles/0/0?level=21", 400},
      {"/v1/worlds/coast/tiles/0/0?level=1&level=1", 400},
      {"/v1/worlds/coast/tiles/0/0?level=nan", 400},
      {"/v1/worlds/coast/tiles/0/0?format=svg", 400},
      {"/v1/worlds/coast/tiles/0/0?zoom=2", 400},
      // Beyond the precision range (2^28 regions a half axis), and beyond 64 bits.
      {"/v1/worlds/coast/tiles/268435456/0", 400},
      {"/v1/worlds/coast/tiles/0/-268435457", 400},
      {"/v1/worlds/coast/tiles/134217728/0?level=1", 400},
      {"/v1/worlds/coast/tiles/99999999999999999999999/0", 400},
      {"/v1/worlds/coast/tiles/-9223372036854775808/0", 400},
      // Over max_query_area (1e6 d^2): a level-6 tile is 1024^2 d^2.
      {"/v1/worlds/coast/tiles/0/0?level=6", 400},
      {"/v1/worlds/nowhere/tiles/0/0", 404},
      {"/v1/worlds/co%61st2/tiles/0/0", 404},
      {"/v1/worlds/coast%zz/tiles/0/0", 400},
      {"/nothing", 404},
  };
  for (const auto& [target, code] : cases) {
    const HttpAnswer answer = Get(target);
    EXPECT_EQ(answer.status, code) << target << ": " << answer.body;
    EXPECT_EQ(answer.content_type, "application/json") << target;
    EXPECT_EQ(answer.headers.at("cache-control"), "no-store") << target;
    const nlohmann::json body = nlohmann::json::parse(answer.body, nullptr, false);
    ASSERT_FALSE(body.is_discarded()) << target;
    EXPECT_FALSE(body["error"]["message"].get<std::string>().empty()) << target;
  }
  // The precision range says OUT_OF_RANGE, as gRPC does.
  const nlohmann::json beyond =
      nlohmann::json::parse(Get("/v1/worlds/coast/tiles/268435456/0").body);
  EXPECT_EQ(beyond["error"]["status"], "OUT_OF_RANGE");
  // The last tiles inside it are served; a percent-escaped name is decoded.
  EXPECT_EQ(Get("/v1/worlds/coast/tiles/268435455/-268435456").status, 200);
  EXPECT_EQ(Get("/v1/worlds/co%61st/tiles/0/0").status, 200);
  EXPECT_EQ(Fetch(http_, http::verb::post, "/v1/worlds/coast/tiles/0/0").status, 405);
  // And the server is still there.
  v1::GetServerInfoResponse info;
  EXPECT_TRUE(server_->Client().GetServerInfo(info).ok());
}

TEST_F(E2eHttpTilesTest, WorldListAndViewerAreServed) {
  const HttpAnswer list = Get("/v1/worlds");
  ASSERT_EQ(list.status, 200);
  const nlohmann::json json = nlohmann::json::parse(list.body);
  EXPECT_EQ(json["default_world"], "default");
  EXPECT_EQ(json["max_level"], 5);  // 512^2 d^2 <= 1e6 < 1024^2
  ASSERT_EQ(json["worlds"].size(), 3u);
  EXPECT_EQ(json["worlds"][0]["name"], "coast");
  EXPECT_EQ(json["worlds"][0]["seed"], "7");
  v1::DescribeWorldRequest describe;
  describe.set_world_name("coast");
  v1::DescribeWorldResponse described;
  ASSERT_TRUE(server_->Client().DescribeWorld(describe, described).ok());
  char fingerprint[17];
  std::snprintf(fingerprint, sizeof fingerprint, "%016llx",
                static_cast<unsigned long long>(described.fingerprint()));
  EXPECT_EQ(json["worlds"][0]["fingerprint"], fingerprint);
  const HttpAnswer page = Get("/");
  EXPECT_EQ(page.status, 200);
  EXPECT_EQ(page.content_type, "text/html; charset=utf-8");
  EXPECT_NE(page.body.find("viewer.js"), std::string::npos);
  EXPECT_EQ(Get("/viewer.js").status, 200);
  EXPECT_EQ(Get("/", {{"If-None-Match", page.headers.at("etag")}}).status, 304);
}

// max_in_flight is shared with gRPC: a tile asked while a cold GetPoints of
// a large square (seconds of generation on one thread) holds the only slot
// is shed with 429 and Retry-After, and served again once the slot is free.
TEST(E2eHttpTileLimitsTest, TilesShareAdmissionWithGrpc) {
  auto server = ScallopdProcess::Start(
      {"--http-listen", "127.0.0.1:0", "--max-in-flight", "1", "--threads", "1"});
  ASSERT_NE(server, nullptr);
  const std::string address = HttpAddress(*server);
  const std::string tile = "/v1/worlds/default/tiles/0/0";
  ASSERT_EQ(Fetch(address, http::verb::get, tile).status, 200);  // now warm
  // The call itself may be shed while a tile holds the slot; it asks again.
  auto holder = std::async(std::launch::async, [&] {
    v1::GetPointsRequest request;
    *request.mutable_rect() = RectToMessage({1e6, 1e6, 1e6 + 990, 1e6 + 990});
    request.set_page_size(1);
    for (;;) {
      v1::GetPointsResponse response;
      const grpc::Status status = server->Client().GetPoints(request, response);
      if (status.error_code() != grpc::StatusCode::RESOURCE_EXHAUSTED) return status;
    }
  });
  int shed = 0;
  while (holder.wait_for(std::chrono::milliseconds(0)) != std::future_status::ready) {
    const HttpAnswer answer = Fetch(address, http::verb::get, tile);
    if (answer.status == 429) {
      ++shed;
      EXPECT_EQ(answer.headers.at("retry-after"), "1");
      EXPECT_NE(answer.body.find("max_in_flight"), std::string::npos);
    } else {
      // Before the call took the slot.
      ASSERT_EQ(answer.status, 200) << answer.body;
    }
  }
  EXPECT_TRUE(holder.get().ok());
  EXPECT_GT(shed, 0);
  EXPECT_EQ(Fetch(address, http::verb::get, tile).status, 200);
}

// The YAML keys: http_listen starts the listener, http_max_age_seconds is
// the tiles' max-age.
TEST(E2eHttpTileConfigTest, YamlStartsTheListenerAndSetsMaxAge) {
  const std::string config = ::testing::TempDir() + "e2e_http_tiles.yaml";
  std::ofstream(config) << "http_listen: 127.0.0.1:0\nhttp_max_age_seconds: 600\n"
                        << "max_http_connections: 8\n";
  auto server = ScallopdProcess::Start({"--config", config});
  ASSERT_NE(server, nullptr);
  const std::string address = HttpAddress(*server);
  const HttpAnswer tile = Fetch(address, http::verb::get, "/v1/worlds/default/tiles/-1/-1.bin");
  EXPECT_EQ(tile.status, 200);
  EXPECT_EQ(tile.headers.at("cache-control"), "public, max-age=600, immutable");
  std::remove(config.c_str());
}

// Tiles share the per-client rate limit with gRPC: with a burst of 2 and a
// token every 1,000 s, the third call of one client (tile or GetPoints) is
// refused with 429 and the limiter's delay in Retry-After.
TEST(E2eHttpTileLimitsTest, TilesShareThePerClientRateLimit) {
  const std::string config = ::testing::TempDir() + "e2e_http_tiles_rate.yaml";
  std::ofstream(config) << "http_listen: 127.0.0.1:0\nrate_limit_per_second: 0.001\n"
                        << "rate_limit_burst: 2\n";
  auto server = ScallopdProcess::Start({"--config", config});
  ASSERT_NE(server, nullptr);
  const std::string address = HttpAddress(*server);
  EXPECT_EQ(Fetch(address, http::verb::get, "/v1/worlds/default/tiles/0/0").status, 200);
  v1::GetPointsRequest request;
  *request.mutable_rect() = RectToMessage({0, 0, 4, 4});
  v1::GetPointsResponse response;
  EXPECT_TRUE(server->Client().GetPoints(request, response).ok());
  const HttpAnswer refused = Fetch(address, http::verb::get, "/v1/worlds/default/tiles/0/1");
  EXPECT_EQ(refused.status, 429) << refused.body;
  EXPECT_NE(refused.body.find("rate_limit_per_second"), std::string::npos) << refused.body;
  EXPECT_GE(std::stoll(refused.headers.at("retry-after")), 900);
  std::remove(config.c_str());
}

// A radius-field world's tiles (issue 24): JSON "rs" and the binary rs array
// hold GetPoints' radii to the bit (the binary size 80 + 32n, flag bit 0);
// the PNG draws each point's disk at R/4, so spots well inside a large
// point's disk are dark and spots beyond every disk white; the world list
// gives the field's range. Constant worlds' tiles have no rs (the fixture's
// tests check flag 0 and 80 + 24n).
TEST(E2eHttpFieldTilesTest, TilesCarryEachPointsRadius) {
  const std::string config = ::testing::TempDir() + "e2e_http_field_tiles.yaml";
  std::ofstream(config) << "http_listen: 127.0.0.1:0\nworlds:\n"
                        << "  dunes: {seed: 4, radius_field: {noise: {r_min: 0.5, r_max: 2, "
                           "frequency: 0.05, noise_seed: 9}}}\n";
  auto server = ScallopdProcess::Start({"--config", config});
  ASSERT_NE(server, nullptr);
  const std::string address = HttpAddress(*server);
  const auto get = [&](const std::string& target) {
    return Fetch(address, http::verb::get, target);
  };
  for (const std::string tile_path :
       {"/v1/worlds/dunes/tiles/0/0", "/v1/worlds/dunes/tiles/-2/1"}) {
    SCOPED_TRACE(tile_path);
    const HttpAnswer json_answer = get(tile_path + ".json");
    ASSERT_EQ(json_answer.status, 200) << json_answer.body;
    const nlohmann::json json = nlohmann::json::parse(json_answer.body);
    const TilePointsRead tile = ReadJsonTile(json_answer.body);
    // A level-0 tile is one region: 6 r_max = 12.
    EXPECT_EQ(tile.rect[2] - tile.rect[0], 12.0);
    const std::vector<double> rs = json.at("rs").get<std::vector<double>>();
    v1::GetPointsRequest request;
    request.set_world_name("dunes");
    *request.mutable_rect() =
        RectToMessage({tile.rect[0], tile.rect[1], tile.rect[2], tile.rect[3]});
    PlanePoints expected;
    std::vector<double> radii;
    ASSERT_TRUE(server->Client().GetAllPoints(request, expected, {}, &radii).ok());
    ASSERT_GT(expected.ids.size(), 20u);
    EXPECT_EQ(tile.ids, expected.ids);
    EXPECT_EQ(rs, radii);  // == on doubles: to the bit
    EXPECT_GT(*std::max_element(rs.begin(), rs.end()), *std::min_element(rs.begin(), rs.end()));

    const HttpAnswer binary = get(tile_path + ".bin");
    ASSERT_EQ(binary.status, 200);
    const size_t n = ReadLittleEndian(binary.body, 8, 4);
    EXPECT_EQ(ReadLittleEndian(binary.body, 6, 2), 1u);  // flag bit 0: rs follows ys
    ASSERT_EQ(binary.body.size(), 80 + 32 * n);
    ASSERT_EQ(n, rs.size());
    for (size_t k = 0; k < n; ++k) {
      ASSERT_EQ(ReadLittleEndian(binary.body, 80 + 8 * k, 8), tile.ids[k]) << k;
      ASSERT_EQ(ReadDouble(binary.body, 80 + 8 * n + 8 * k), tile.xs[k]) << k;
      ASSERT_EQ(ReadDouble(binary.body, 80 + 24 * n + 8 * k), rs[k]) << k;
    }

    // The PNG: disks of R/4 (at least 0.75 pixel), neighbours' disks across the edge.
    const HttpAnswer png = get(tile_path + ".png");
    ASSERT_EQ(png.status, 200);
    int width = 0, height = 0;
    const std::vector<uint8_t> pixels = DecodeGreyPng(png.body, width, height);
    ASSERT_EQ(width, 256);
    const double pixel = (tile.rect[2] - tile.rect[0]) / 256;
    *request.mutable_rect() =
        RectToMessage({tile.rect[0] - 1, tile.rect[1] - 1, tile.rect[2] + 1, tile.rect[3] + 1});
    PlanePoints around;
    std::vector<double> around_radii;
    ASSERT_TRUE(server->Client().GetAllPoints(request, around, {}, &around_radii).ok());
    int white = 0, dark_inside_large_disks = 0;
    for (int row = 0; row < 256; ++row) {
      for (int column = 0; column < 256; ++column) {
        const double x = tile.rect[0] + (column + 0.5) * pixel;
        const double y = tile.rect[3] - (row + 0.5) * pixel;
        bool beyond_every_disk = true, deep_in_a_large_disk = false;
        for (size_t k = 0; k < around.positions.size(); ++k) {
          const double distance = std::hypot(around.positions[k].x - x, around.positions[k].y - y);
          const double radius = std::max(around_radii[k] / 4, 0.75 * pixel);
          if (distance <= radius + pixel) beyond_every_disk = false;
          // Inside this disk by a pixel, and outside the disk r_min / 4 would draw.
          if (distance < radius - pixel && distance > 0.5 / 4 + pixel) deep_in_a_large_disk = true;
        }
        const uint8_t value = pixels[row * 256 + column];
        if (beyond_every_disk) {
          ++white;
          ASSERT_EQ(value, 255) << "row " << row << " column " << column;
        }
        if (deep_in_a_large_disk) {
          ++dark_inside_large_disks;
          ASSERT_LT(value, 128) << "row " << row << " column " << column;
        }
      }
    }
    EXPECT_GT(white, 256 * 256 / 4);
    EXPECT_GT(dark_inside_large_disks, 100);
  }
  const nlohmann::json list = nlohmann::json::parse(get("/v1/worlds").body);
  bool listed = false;
  for (const auto& world : list.at("worlds")) {
    if (world.at("name") != "dunes") continue;
    listed = true;
    EXPECT_EQ(world.at("field_kind"), "noise");
    EXPECT_EQ(world.at("r_min").get<double>(), 0.5);
    EXPECT_EQ(world.at("r_max").get<double>(), 2.0);
    EXPECT_EQ(world.at("region_side").get<double>(), 12.0);
  }
  EXPECT_TRUE(listed);
  EXPECT_EQ(list.at("tile_format_version"), 3);
  // A constant world's tile has no rs.
  EXPECT_FALSE(nlohmann::json::parse(get("/v1/worlds/default/tiles/0/0.json").body).contains("rs"));
  std::remove(config.c_str());
}

TEST(E2eHttpTileAuthTest, TilesNeedATokenForTheirWorld) {
  const std::string tokens = ::testing::TempDir() + "e2e_http_tiles_tokens";
  std::ofstream(tokens) << "any-world-token-0123456789\ncoast-only-token-0123456789 coast\n";
  client::ConnectionOptions with_token;
  with_token.token = "any-world-token-0123456789";
  auto server = ScallopdProcess::Start(
      {"--http-listen", "127.0.0.1:0", "--auth-tokens", tokens, "--world", "coast:7:1:a3"},
      "127.0.0.1:0", with_token);
  ASSERT_NE(server, nullptr);
  const std::string address = HttpAddress(*server);
  auto code = [&](const std::string& target, const std::string& token) {
    std::map<std::string, std::string> headers;
    if (!token.empty()) headers["Authorization"] = "Bearer " + token;
    return Fetch(address, http::verb::get, target, headers).status;
  };
  EXPECT_EQ(code("/v1/worlds/coast/tiles/0/0", ""), 401);
  EXPECT_EQ(code("/v1/worlds/coast/tiles/0/0", "wrong-token-0123456789"), 401);
  EXPECT_EQ(code("/v1/worlds/coast/tiles/0/0", "coast-only-token-0123456789"), 200);
  EXPECT_EQ(code("/v1/worlds/default/tiles/0/0", "coast-only-token-0123456789"), 403);
  EXPECT_EQ(code("/v1/worlds/default/tiles/0/0", "any-world-token-0123456789"), 200);
  EXPECT_EQ(code("/v1/worlds", ""), 401);
  // With tokens a shared cache must not keep tiles for callers without one.
  const HttpAnswer tile = Fetch(address, http::verb::get, "/v1/worlds/coast/tiles/0/0",
                                {{"Authorization", "Bearer coast-only-token-0123456789"}});
  EXPECT_TRUE(tile.headers.at("cache-control").starts_with("private"))
      << tile.headers.at("cache-control");
  // A token limited to coast sees only coast in the list.
  const nlohmann::json list =
      nlohmann::json::parse(Fetch(address, http::verb::get, "/v1/worlds",
                                  {{"Authorization", "Bearer coast-only-token-0123456789"}})
                                .body);
  ASSERT_EQ(list["worlds"].size(), 1u);
  EXPECT_EQ(list["worlds"][0]["name"], "coast");
  // The page itself holds no data: open.
  EXPECT_EQ(code("/", ""), 200);
  std::remove(tokens.c_str());
}

// Layered worlds' tiles (issue 19): every point's layer and spacing, in the
// order and bits GetPoints gives them; ETags of tile format version 4 for
// them alone, while a plain world's stay version 3's; the PNG in colour.
class E2eLayeredTilesTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const std::string config = ::testing::TempDir() + "/e2e_layered_tiles_test.yaml";
    std::ofstream out(config);
    out << "worlds:\n"
        << "  forest: {seed: 7, layers: [{name: trees, min_distance: 8},\n"
        << "           {name: bushes, radius_field: {noise: {r_min: 2.5, r_max: 3.5,"
           " frequency: 0.02}}}, {name: rocks, min_distance: 1.5}]}\n"
        << "  coast: {seed: 7, min_distance: 1, algorithm: a3}\n";
    out.close();
    server_ =
        ScallopdProcess::Start({"--config", config, "--http-listen", "127.0.0.1:0"}).release();
    ASSERT_NE(server_, nullptr);
    http_ = HttpAddress(*server_);
    ASSERT_FALSE(http_.empty()) << server_->Log();
  }
  static void TearDownTestSuite() { delete server_; }

  static inline ScallopdProcess* server_ = nullptr;
  static inline std::string http_;
};

TEST_F(E2eLayeredTilesTest, TilesCarryEachPointsLayerAsGetPointsDoes) {
  const std::string target = "/v1/worlds/forest/tiles/-1/0";
  const HttpAnswer json = Fetch(http_, http::verb::get, target + ".json?level=1");
  ASSERT_EQ(json.status, 200) << json.body;
  const nlohmann::json tile = nlohmann::json::parse(json.body);
  EXPECT_EQ(tile.at("layer_names"), nlohmann::json({"trees", "bushes", "rocks"}));
  // The tile's rectangle by GetPoints: the same points, layers and spacings.
  v1::GetPointsRequest request;
  request.set_world_name("forest");
  const auto rect = tile.at("rect").get<std::vector<double>>();
  *request.mutable_rect() = RectToMessage({rect[0], rect[1], rect[2], rect[3]});
  PlanePoints points;
  std::vector<double> radii;
  ASSERT_TRUE(server_->Client().GetAllPoints(request, points, {}, &radii).ok());
  ASSERT_GT(points.ids.size(), 50u);
  const auto layers = tile.at("layers").get<std::vector<int>>();
  const auto rs = tile.at("rs").get<std::vector<double>>();
  const auto xs = tile.at("xs").get<std::vector<double>>();
  ASSERT_EQ(layers.size(), points.ids.size());
  ASSERT_EQ(rs.size(), points.ids.size());
  for (size_t k = 0; k < points.ids.size(); ++k) {
    EXPECT_EQ(std::stoull(tile.at("ids")[k].get<std::string>()), points.ids[k]);
    EXPECT_EQ(xs[k], points.positions[k].x);
    EXPECT_EQ(layers[k], points.layers[k]);
    EXPECT_EQ(rs[k], radii[k]);  // a field layer: GetPoints sends each point's spacing too
  }
  for (const int layer : {0, 1, 2}) {
    EXPECT_NE(std::count(layers.begin(), layers.end(), layer), 0) << layer;
  }
  // Binary: flags rs and layers, 34 bytes a point, the same layers.
  const HttpAnswer binary = Fetch(http_, http::verb::get, target + ".bin?level=1");
  ASSERT_EQ(binary.status, 200);
  const size_t n = points.ids.size();
  EXPECT_EQ(ReadLittleEndian(binary.body, 6, 2), 3u);
  ASSERT_EQ(binary.body.size(), 80 + 34 * n);
  for (size_t k = 0; k < n; ++k) {
    EXPECT_EQ(ReadDouble(binary.body, 80 + 24 * n + 8 * k), rs[k]);
    EXPECT_EQ(ReadLittleEndian(binary.body, 80 + 32 * n + 2 * k, 2),
              static_cast<uint64_t>(layers[k]));
  }
  // ETags: version 4 for the layered world, 3 (unchanged) for a plain one.
  EXPECT_NE(json.headers.at("etag").find(".t4."), std::string::npos) << json.headers.at("etag");
  const HttpAnswer plain = Fetch(http_, http::verb::get, "/v1/worlds/coast/tiles/0/0.bin");
  EXPECT_NE(plain.headers.at("etag").find(".t3."), std::string::npos);
  EXPECT_EQ(ReadLittleEndian(plain.body, 6, 2), 0u);
  // The world list names the layers and their colours.
  const nlohmann::json list =
      nlohmann::json::parse(Fetch(http_, http::verb::get, "/v1/worlds").body);
  for (const auto& world : list.at("worlds")) {
    if (world.at("name") != "forest") continue;
    ASSERT_EQ(world.at("layers").size(), 3u);
    EXPECT_EQ(world.at("layers")[2].at("name"), "rocks");
    EXPECT_EQ(world.at("tile_format_version"), 4);
  }
  // PNG: in colour, the trees' green among the pixels.
  const HttpAnswer png = Fetch(http_, http::verb::get, target + ".png?level=1");
  ASSERT_EQ(png.status, 200);
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  ASSERT_TRUE(png_image_begin_read_from_memory(&image, png.body.data(), png.body.size()));
  EXPECT_EQ(image.format & PNG_FORMAT_FLAG_COLOR, PNG_FORMAT_FLAG_COLOR);
  image.format = PNG_FORMAT_RGB;
  std::vector<uint8_t> pixels(PNG_IMAGE_SIZE(image));
  ASSERT_TRUE(png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr));
  int green = 0;
  for (size_t p = 0; p + 2 < pixels.size(); p += 3) {
    green += pixels[p] == 0x2e && pixels[p + 1] == 0x7d && pixels[p + 2] == 0x32;
  }
  EXPECT_GT(green, 0);
}

}  // namespace
}  // namespace scallop::testing
