// Page tokens for GetPoints: opaque to clients, tamper-evident, and bound to
// the world and rectangle they page through. Hex of
//   version (1 byte) | offset (8) | query digest (8) | HMAC-SHA256 tag (16).
#pragma once

#include <cstdint>
#include <string>

#include "scallop/base/status.h"
#include "scallop/geometry/rect.h"
#include "scallop/plane/plane_engine.h"
#include "scallop/plane/world.h"

namespace scallop::server {

class PageTokenCodec {
 public:
  // Why a keyed MAC rather than a plain checksum: a checksum a client can
  // recompute would let an edited token pass as valid and page silently into
  // the wrong place. The key is the configured secret or, when none is set,
  // derived from the world set, so replicas sharing a configuration (and one
  // server across restarts) accept each other's tokens without coordination.
  // A derived key is guessable by whoever knows the configuration; that is
  // acceptable because a token grants nothing a fresh request could not: the
  // tag is there to catch corrupted, truncated and edited tokens loudly.
  explicit PageTokenCodec(std::string key) : key_(std::move(key)) {}

  // The token for the page starting at `offset` of (world, rect), and for a
  // layered world its layer filter (NormalisedLayerMask): the offset counts
  // the filtered points layer by layer, so it names (layer, region, index).
  // A world without layers ignores the mask (its tokens are as before). O(1).
  std::string Encode(const World& world, const Rect& rect, uint64_t offset,
                     LayerMask layers = kAllLayers) const;

  // The offset a token encodes. INVALID_ARGUMENT naming page_token when it is
  // malformed, its tag does not match, or it was made for another world, rect
  // or layer filter.
  StatusOr<uint64_t> Decode(const std::string& token, const World& world, const Rect& rect,
                            LayerMask layers = kAllLayers) const;

 private:
  std::string Tag(const std::string& body) const;

  std::string key_;
};

}  // namespace scallop::server
