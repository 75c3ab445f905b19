// FollowSession: a synchronous client of scallopd's Follow stream, one
// viewport update at a time, and FollowedPoints, the store a follower keeps:
// points by region, evictions applied, so it can name its held regions when
// it resumes. For the CLI, the tests and the benchmark.
#pragma once

#include <grpcpp/grpcpp.h>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <vector>

#include "scallop/plane/plane_engine.h"
#include "scallop/plane/region_layout.h"
#include "scallop/v1/scallop.grpc.pb.h"
#include "scallop_client.h"

namespace scallop::client {

// One Follow call. Not thread-safe: one thread drives a session.
class FollowSession {
 public:
  // Opens the call (connecting lazily). `options.timeout` is the deadline of
  // the whole call.
  explicit FollowSession(const ScallopClient& client, const CallOptions& options = {});
  ~FollowSession();  // cancels the call if it is still open
  FollowSession(const FollowSession&) = delete;
  FollowSession& operator=(const FollowSession&) = delete;

  // Sends `request` (set world or world_name in the first only) and reads
  // its answer, calling on_response for every message, up to the one with
  // update_complete. The sequence is set here (1, 2, ...). On failure the
  // call is over and the result is its final status (the server's message
  // naming the bad field, or why it dropped the call).
  grpc::Status Update(v1::FollowRequest request,
                      const std::function<void(const v1::FollowResponse&)>& on_response);

  // Sends `request` and returns at once without reading the answer: for
  // tests of a client that stops reading. Then call Finish.
  bool SendOnly(v1::FollowRequest request);

  // Closes our side and returns the call's status (OK when the server
  // finished normally). Messages still unread are discarded.
  grpc::Status Finish();

 private:
  std::unique_ptr<v1::Scallop::Stub> stub_;
  grpc::ClientContext context_;
  std::unique_ptr<grpc::ClientReaderWriter<v1::FollowRequest, v1::FollowResponse>> stream_;
  uint64_t next_sequence_ = 1;
  bool finished_ = false;
  grpc::Status final_status_;
};

// The points a follower holds, by region: chunks added, evictions applied.
class FollowedPoints {
 public:
  // Applies one message. INTERNAL when a chunk's arrays differ in length.
  grpc::Status Apply(const v1::FollowResponse& response);

  // Adds a whole region the follower got elsewhere (to declare it held).
  void AddRegion(RegionKey key, const PlanePoints& points);

  // Regions held, in (i, j) order, and a region's points (empty if none).
  std::vector<RegionKey> Regions() const;
  const PlanePoints& PointsOf(RegionKey key) const;
  // Points held in all, and whether `id` of region `key` is among them.
  int64_t Count() const;
  bool Holds(RegionKey key, uint64_t id) const;

 private:
  std::map<RegionKey, PlanePoints> regions_;
};

}  // namespace scallop::client
