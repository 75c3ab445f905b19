// Follow: a bidirectional stream that follows a moving viewport. Each update
// is read only once the answer to the previous one is written, so a slow
// client holds back the server instead of filling its memory; a write that
// does not complete within follow_stall_seconds, or no update within
// follow_idle_seconds, ends the call with DEADLINE_EXCEEDED (see
// docs/streaming.md for why that code).
#include <boost/asio/post.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "encoded_points.h"
#include "scallop/plane/viewport_tracker.h"
#include "server/admitted_stream.h"
#include "server/follow_prefetch.h"
#include "server/scallop_service.h"
#include "server/stall_timer.h"
#include "server/status_mapping.h"

namespace scallop::server {
namespace {

ViewportUpdate UpdateFromMessage(const v1::FollowRequest& request) {
  ViewportUpdate update{.viewport = RectFromMessage(request.viewport()),
                        .velocity = {request.velocity_x(), request.velocity_y()},
                        .keep_margin = request.keep_margin()};
  update.held_regions.reserve(static_cast<size_t>(request.held_regions_size()));
  for (const v1::RegionKey& key : request.held_regions()) {
    update.held_regions.push_back({key.i(), key.j()});
  }
  return update;
}

void SetKey(RegionKey key, v1::RegionKey& message) {
  message.set_i(key.i);
  message.set_j(key.j);
}

// Whether the message's value names `encoding` (PACKED and UNSPECIFIED alike).
bool SameEncoding(int value, PointEncoding encoding) {
  const StatusOr<PointEncoding> named = PointEncodingFromMessage(value);
  return named.ok() && *named == encoding;
}

}  // namespace

class FollowReactor final
    : public AdmittedStream<grpc::ServerBidiReactor<v1::FollowRequest, v1::FollowResponse>> {
 public:
  FollowReactor(ServiceContext& shared, grpc::CallbackServerContext* context)
      : AdmittedStream(shared, "Follow"),
        shared_(shared),
        context_(context),
        stall_seconds_(shared.config.follow_stall_seconds),
        idle_seconds_(shared.config.follow_idle_seconds),
        stall_message_(std::make_shared<const std::string>(StallStatus().error_message())),
        idle_message_(std::make_shared<const std::string>(IdleStatus().error_message())),
        timer_(context) {
    if (!Admit(*context, shared.Authorize(*context))) return;
    Read();
  }

  void OnReadDone(bool ok) override {
    timer_.Disarm();
    if (!ok) {
      // The client closed its side (WritesDone), sent nothing for too long,
      // or the call broke.
      FinishWith(timer_.fired() ? IdleStatus()
                 : context_->IsCancelled()
                     ? grpc::Status(grpc::StatusCode::CANCELLED, "follow: cancelled")
                     : grpc::Status::OK);
      return;
    }
    boost::asio::post(shared_.request_pool, [this] { AnswerUpdate(); });
  }

  void OnWriteDone(bool ok) override {
    timer_.Disarm();
    if (!ok) {
      FinishWith(timer_.fired()
                     ? StallStatus()
                     : grpc::Status(grpc::StatusCode::CANCELLED,
                                    "follow: the client went away or the call was cancelled"));
      return;
    }
    WriteNextOrRead();
  }

  void OnDone() override { delete this; }

 private:
  grpc::Status StallStatus() const {
    return {grpc::StatusCode::DEADLINE_EXCEEDED,
            "follow: the client read nothing for " + SecondsText(stall_seconds_) +
                " s (follow_stall_seconds); reconnect and list held_regions to resume"};
  }

  grpc::Status IdleStatus() const {
    return {grpc::StatusCode::DEADLINE_EXCEEDED,
            "follow: the client sent no update for " + SecondsText(idle_seconds_) +
                " s (follow_idle_seconds); reconnect and list held_regions to resume"};
  }

  // Waits for the next update, for at most follow_idle_seconds.
  void Read() {
    timer_.Arm(idle_seconds_, idle_message_);
    StartRead(&request_);
  }

  // Runs on the request pool: validates the update, moves the tracker,
  // gathers the points newly in view and queues the answer's messages.
  void AnswerUpdate() {
    if (grpc::Status status = PrepareUpdate(); !status.ok()) {
      FinishWith(status);
      return;
    }
    const ViewportUpdate update = UpdateFromMessage(request_);
    const std::vector<RegionKey> evicted = tracker_->Update(update);
    // Generation (if the prefetch did not get there first) happens here,
    // rank by rank in parallel on the engine's pool.
    StatusOr<PlanePoints> in_view = shared_.engine.Points(world_, update.viewport);
    if (!in_view.ok()) {
      FinishWith(ToGrpcStatus(in_view.status()));
      return;
    }
    StatusOr<std::vector<RegionChunk>> chunks = tracker_->TakeUnsent(*in_view);
    if (!chunks.ok()) {
      FinishWith(ToGrpcStatus(chunks.status()));
      return;
    }
    if (std::optional<Rect> ahead = tracker_->PrefetchArea(update)) prefetch_->Request(*ahead);

    // Evictions ride on the first message, the completion flag on the last.
    answer_.clear();
    answer_.resize(std::max<size_t>(chunks->size(), 1));
    for (v1::FollowResponse& response : answer_) response.set_sequence(request_.sequence());
    for (const RegionKey& key : evicted) SetKey(key, *answer_.front().add_evicted());
    for (size_t n = 0; n < chunks->size(); ++n) {
      const RegionChunk& chunk = (*chunks)[n];
      v1::PointsChunk& message = *answer_[n].mutable_chunk();
      AppendPoints(chunk.points, 0, chunk.points.ids.size(), *message.mutable_points(), world_,
                   encoding_);
      message.set_region_i(chunk.key.i);
      message.set_region_j(chunk.key.j);
      log_.add_points(static_cast<int64_t>(chunk.points.ids.size()));
    }
    answer_.back().set_update_complete(true);
    next_message_ = 0;
    WriteNextOrRead();
  }

  // The world (first message only) and the update's validity.
  grpc::Status PrepareUpdate() {
    if (!tracker_) {
      // The token was checked at the start; its worlds only now, with the first message.
      if (grpc::Status status = shared_.Authorize(*context_, request_); !status.ok()) {
        return status;
      }
      ResolvedWorld resolved;
      if (grpc::Status status = shared_.worlds.Resolve(request_, resolved); !status.ok()) {
        return status;
      }
      StatusOr<PointEncoding> encoding = PointEncodingFromMessage(request_.encoding());
      if (!encoding.ok()) return ToGrpcStatus(encoding.status());
      encoding_ = *encoding;
      world_ = resolved.world;
      log_.set_world(world_.Describe());
      tracker_.emplace(world_);
      prefetch_.emplace(shared_.engine, shared_.request_pool, world_);
    } else if (request_.world_choice_case() != v1::FollowRequest::WORLD_CHOICE_NOT_SET) {
      return {grpc::StatusCode::INVALID_ARGUMENT,
              "world: set only in the first message of a Follow call (world or world_name)"};
    } else if (request_.encoding() != v1::POINT_ENCODING_UNSPECIFIED &&
               !SameEncoding(request_.encoding(), encoding_)) {
      return {grpc::StatusCode::INVALID_ARGUMENT,
              "encoding: the first message of a Follow call sets it for the call; later "
              "messages leave it unset or repeat it"};
    }
    if (!request_.has_viewport()) {
      return {grpc::StatusCode::INVALID_ARGUMENT,
              "viewport: required, the half-open rectangle [x0, x1) x [y0, y1)"};
    }
    log_.set_rect(RectFromMessage(request_.viewport()));
    return ToGrpcStatus(ValidateViewportUpdate(world_, UpdateFromMessage(request_),
                                               shared_.config.max_follow_area));
  }

  void WriteNextOrRead() {
    if (next_message_ == answer_.size()) {
      Read();
      return;
    }
    const v1::FollowResponse& response = answer_[next_message_++];
    timer_.Arm(stall_seconds_, stall_message_);
    StartWrite(&response);
  }

  ServiceContext& shared_;
  grpc::CallbackServerContext* context_;
  const double stall_seconds_;
  const double idle_seconds_;
  const std::shared_ptr<const std::string> stall_message_;
  const std::shared_ptr<const std::string> idle_message_;
  StallTimer timer_;  // one wait at a time: a write, or the next update
  World world_;
  PointEncoding encoding_ = PointEncoding::kPacked;  // set by the first update
  std::optional<ViewportTracker> tracker_;           // set by the first update
  std::optional<FollowPrefetch> prefetch_;           // set by the first update
  v1::FollowRequest request_;                        // the update being read or answered
  std::vector<v1::FollowResponse> answer_;           // the messages of the current answer
  size_t next_message_ = 0;
};

grpc::ServerBidiReactor<v1::FollowRequest, v1::FollowResponse>* ScallopService::Follow(
    grpc::CallbackServerContext* context) {
  return new FollowReactor(shared_, context);
}

}  // namespace scallop::server
