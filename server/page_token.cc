// Page token encoding: a little-endian body, an HMAC-SHA256 tag, hex text.
#include "server/page_token.h"

#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/hmac.h>

#include <bit>

#include "scallop/random/rng.h"
#include "server/layer_choice.h"

namespace scallop::server {
namespace {

constexpr char kTokenVersion = 1;
constexpr size_t kBodyBytes = 1 + 8 + 8;
constexpr size_t kTagBytes = 16;  // 128 bits: guessing a valid tag is hopeless

void AppendWord(std::string& out, uint64_t word) {
  for (int b = 0; b < 8; ++b) out.push_back(static_cast<char>((word >> (8 * b)) & 0xff));
}

uint64_t ReadWord(const std::string& in, size_t at) {
  uint64_t word = 0;
  for (int b = 0; b < 8; ++b) word |= uint64_t{static_cast<unsigned char>(in[at + b])} << (8 * b);
  return word;
}

// The bits of a coordinate, with -0 read as +0: they name the same
// rectangle, and a token minted for one must page the other.
uint64_t CoordinateBits(double value) { return std::bit_cast<uint64_t>(value + 0.0); }

uint64_t QueryDigest(const World& world, const Rect& rect, LayerMask layers) {
  const uint64_t digest =
      HashWords({world.fingerprint(), CoordinateBits(rect.x0), CoordinateBits(rect.y0),
                 CoordinateBits(rect.x1), CoordinateBits(rect.y1)});
  // A layered world's pages depend on the filter too; other worlds' digests stay as they were.
  if (world.layers() == nullptr) return digest;
  return HashWords({digest, NormalisedLayerMask(world, layers)});
}

std::string ToHex(const std::string& bytes) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string hex;
  for (unsigned char c : bytes) {
    hex.push_back(kDigits[c >> 4]);
    hex.push_back(kDigits[c & 15]);
  }
  return hex;
}

bool FromHex(const std::string& hex, std::string& bytes) {
  auto nibble = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    return -1;
  };
  if (hex.size() % 2 != 0) return false;
  for (size_t k = 0; k < hex.size(); k += 2) {
    const int high = nibble(hex[k]), low = nibble(hex[k + 1]);
    if (high < 0 || low < 0) return false;
    bytes.push_back(static_cast<char>(high * 16 + low));
  }
  return true;
}

}  // namespace

std::string PageTokenCodec::Tag(const std::string& body) const {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  HMAC(EVP_sha256(), key_.data(), static_cast<int>(key_.size()),
       reinterpret_cast<const unsigned char*>(body.data()), body.size(), digest, &length);
  return std::string(reinterpret_cast<const char*>(digest), kTagBytes);
}

std::string PageTokenCodec::Encode(const World& world, const Rect& rect, uint64_t offset,
                                   LayerMask layers) const {
  std::string body(1, kTokenVersion);
  AppendWord(body, offset);
  AppendWord(body, QueryDigest(world, rect, layers));
  return ToHex(body + Tag(body));
}

StatusOr<uint64_t> PageTokenCodec::Decode(const std::string& token, const World& world,
                                          const Rect& rect, LayerMask layers) const {
  std::string bytes;
  if (!FromHex(token, bytes) || bytes.size() != kBodyBytes + kTagBytes ||
      bytes[0] != kTokenVersion) {
    return InvalidArgument("page_token: malformed; pass the next_page_token of the previous page");
  }
  const std::string body = bytes.substr(0, kBodyBytes);
  // Constant time, so response timing does not reveal how much of a tag matched.
  if (CRYPTO_memcmp(Tag(body).data(), bytes.data() + kBodyBytes, kTagBytes) != 0) {
    return InvalidArgument(
        "page_token: tampered with or issued by a differently configured server");
  }
  if (ReadWord(body, 9) != QueryDigest(world, rect, layers)) {
    return InvalidArgument(
        "page_token: issued for another world or rect than this request's (or another layers "
        "filter)");
  }
  return ReadWord(body, 1);
}

}  // namespace scallop::server
