// FollowSession over a synchronous bidirectional stream, and FollowedPoints.
#include "follow_client.h"

#include <algorithm>

#include "world_messages.h"

namespace scallop::client {

FollowSession::FollowSession(const ScallopClient& client, const CallOptions& options)
    : stub_(v1::Scallop::NewStub(client.channel())) {
  client.Configure(context_, options);
  stream_ = stub_->Follow(&context_);
}

FollowSession::~FollowSession() {
  if (!finished_) {
    context_.TryCancel();
    Finish();
  }
}

bool FollowSession::SendOnly(v1::FollowRequest request) {
  request.set_sequence(next_sequence_++);
  return !finished_ && stream_->Write(request);
}

grpc::Status FollowSession::Update(
    v1::FollowRequest request, const std::function<void(const v1::FollowResponse&)>& on_response) {
  if (finished_) return final_status_;
  const uint64_t sequence = next_sequence_;
  // A failed write means the call is over; its status says why.
  if (!SendOnly(std::move(request))) return Finish();
  v1::FollowResponse response;
  while (stream_->Read(&response)) {
    if (response.sequence() != sequence) {
      context_.TryCancel();
      Finish();
      return {grpc::StatusCode::INTERNAL, "malformed reply: sequence " +
                                              std::to_string(response.sequence()) + ", expected " +
                                              std::to_string(sequence)};
    }
    on_response(response);
    if (response.update_complete()) return grpc::Status::OK;
  }
  return Finish();
}

grpc::Status FollowSession::Finish() {
  if (finished_) return final_status_;
  finished_ = true;
  stream_->WritesDone();
  // Finish needs every message read first; drain what is left.
  v1::FollowResponse unread;
  while (stream_->Read(&unread)) {
  }
  final_status_ = stream_->Finish();
  return final_status_;
}

grpc::Status FollowedPoints::Apply(const v1::FollowResponse& response) {
  for (const v1::RegionKey& key : response.evicted()) regions_.erase({key.i(), key.j()});
  if (!response.has_chunk()) return grpc::Status::OK;
  const v1::PointsChunk& chunk = response.chunk();
  const Status read = ReadPoints(chunk.points(), regions_[{chunk.region_i(), chunk.region_j()}]);
  if (!read.ok()) return {grpc::StatusCode::INTERNAL, "malformed reply: " + read.message()};
  return grpc::Status::OK;
}

void FollowedPoints::AddRegion(RegionKey key, const PlanePoints& points) {
  PlanePoints& held = regions_[key];
  for (size_t n = 0; n < points.ids.size(); ++n) {
    if (Holds(key, points.ids[n])) continue;
    held.positions.push_back(points.positions[n]);
    held.ids.push_back(points.ids[n]);
  }
}

std::vector<RegionKey> FollowedPoints::Regions() const {
  std::vector<RegionKey> keys;
  for (const auto& [key, points] : regions_) keys.push_back(key);
  return keys;
}

const PlanePoints& FollowedPoints::PointsOf(RegionKey key) const {
  static const PlanePoints kNone;
  const auto it = regions_.find(key);
  return it == regions_.end() ? kNone : it->second;
}

int64_t FollowedPoints::Count() const {
  int64_t count = 0;
  for (const auto& [key, points] : regions_) count += static_cast<int64_t>(points.ids.size());
  return count;
}

bool FollowedPoints::Holds(RegionKey key, uint64_t id) const {
  const std::vector<uint64_t>& ids = PointsOf(key).ids;
  return std::find(ids.begin(), ids.end(), id) != ids.end();
}

}  // namespace scallop::client
