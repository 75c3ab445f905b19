// Page tokens (server/page_token.h) from arbitrary client text: Decode never
// crashes, accepts only tokens Encode made for the same world and rectangle
// (the fuzzer cannot forge an HMAC tag, so what it finds is what the seeds
// hold), and every accepted token re-encodes to itself and decodes again to
// the same offset. The world, rectangle and an offset also come from the
// input, so Encode and Decode round-trip on arbitrary doubles too.
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>

#include "fuzz/fuzz_check.h"
#include "server/page_token.h"

namespace {

double ReadDouble(const uint8_t*& data, size_t& size) {
  uint64_t bits = 0;
  const size_t n = size < 8 ? size : 8;
  std::memcpy(&bits, data, n);
  data += n;
  size -= n;
  return std::bit_cast<double>(bits);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using scallop::Rect;
  using scallop::World;
  using scallop::server::PageTokenCodec;
  // The key a server derives or is given; fixed so the seeds' tokens decode.
  static const PageTokenCodec codec("scallop-fuzz-page-token-key");
  static const World world = *World::Create({.seed = 1});

  // The seeds' tokens are for this world and rect [0, 64) x [0, 64).
  const Rect seed_rect{0, 0, 64, 64};
  const std::string token(reinterpret_cast<const char*>(data), size);
  const scallop::StatusOr<uint64_t> offset = codec.Decode(token, world, seed_rect);
  if (offset.ok()) {
    SCALLOP_FUZZ_CHECK(codec.Encode(world, seed_rect, *offset) == token,
                       "token " + token + " decodes but does not re-encode to itself");
  } else {
    SCALLOP_FUZZ_CHECK(offset.status().message().starts_with("page_token: "),
                       "error does not name page_token: " + offset.status().message());
  }

  // Round trip on a rectangle and offset read from the input's first bytes.
  const Rect rect{ReadDouble(data, size), ReadDouble(data, size), ReadDouble(data, size),
                  ReadDouble(data, size)};
  const uint64_t any_offset = std::bit_cast<uint64_t>(ReadDouble(data, size));
  const std::string minted = codec.Encode(world, rect, any_offset);
  const scallop::StatusOr<uint64_t> decoded = codec.Decode(minted, world, rect);
  SCALLOP_FUZZ_CHECK(decoded.ok() && *decoded == any_offset,
                     "a minted token does not decode to its offset: " + minted);
  // -0 and +0 name the same rectangle (issue 20): the token pages both.
  const Rect negated_zero{rect.x0 == 0 ? -rect.x0 : rect.x0, rect.y0 == 0 ? -rect.y0 : rect.y0,
                          rect.x1, rect.y1};
  const scallop::StatusOr<uint64_t> same = codec.Decode(minted, world, negated_zero);
  SCALLOP_FUZZ_CHECK(same.ok() && *same == any_offset,
                     "a token is refused for the same rectangle with -0: " + minted);
  return 0;
}
