// The null server's answers: real GetPoints responses (points of a real world
// for tiles of the benchmark's size), serialized once at start-up and then
// handed out as shared byte buffers, so that serving one costs the transport
// alone.
#pragma once

#include <grpcpp/support/byte_buffer.h>

#include <cstdint>
#include <vector>

#include "scallop/plane/world.h"

namespace scallop::load {

struct NullResponseOptions {
  World world;            // the points' world: scallopd's default is seed 1, d 1, A3
  double tile_side = 64;  // in world units
  int count = 64;         // distinct responses, from tiles at random places
  uint64_t seed = 1;      // places the tiles
};

// Generates `count` tiles with the core's PlaneEngine and serializes each
// GetPointsResponse (points, world, no page token) once. Cost: generating
// count * tile_side^2 / d^2 points or so, about a second for the defaults.
std::vector<grpc::ByteBuffer> BuildNullResponses(const NullResponseOptions& options);

}  // namespace scallop::load
