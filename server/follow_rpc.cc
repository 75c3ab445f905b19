// Follow: a bidirectional stream that follows a moving viewport. Each update
// is read only once the answer to the previous one is written, so a slow
// client holds back the server instead of filling its memory; a write that
// does not complete within follow_stall_seconds ends the call with
// DEADLINE_EXCEEDED (see docs/streaming.md for why that code).
#include <grpc/grpc.h>
#include <grpcpp/alarm.h>

#include <atomic>
#include <boost/asio/post.hpp>
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "admitted_stream.h"
#include "follow_prefetch.h"
#include "scallop/plane/viewport_tracker.h"
#include "scallop_service.h"
#include "status_mapping.h"
#include "world_messages.h"

namespace scallop::server {
namespace {

// What a stall alarm touches: the call (a reference of our own, so it stays
// valid however late the alarm runs) and which write is being watched.
// Shared with the alarm callbacks, which can outlive the reactor.
struct StallWatch {
  explicit StallWatch(grpc_call* call_to_cancel) : call(call_to_cancel) { grpc_call_ref(call); }
  ~StallWatch() { grpc_call_unref(call); }
  StallWatch(const StallWatch&) = delete;
  StallWatch& operator=(const StallWatch&) = delete;

  grpc_call* const call;
  std::atomic<uint64_t> watched_write = 0;  // 0: no write pending
  std::atomic<bool> stalled = false;
  std::string message;  // the status message a stall ends the call with
};

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

}  // namespace

class FollowReactor final
    : public AdmittedStream<grpc::ServerBidiReactor<v1::FollowRequest, v1::FollowResponse>> {
 public:
  FollowReactor(ScallopService& service, grpc::CallbackServerContext* context)
      : AdmittedStream(service.in_flight_, "Follow", service.metrics_),
        service_(service),
        context_(context),
        stall_seconds_(service.config_.follow_stall_seconds),
        stall_watch_(std::make_shared<StallWatch>(context->c_call())) {
    stall_watch_->message = StallStatus().error_message();
    if (!Admit()) return;
    StartRead(&request_);
  }

  void OnReadDone(bool ok) override {
    if (!ok) {
      // The client closed its side (WritesDone), or the call broke.
      FinishWith(context_->IsCancelled()
                     ? grpc::Status(grpc::StatusCode::CANCELLED, "follow: cancelled")
                     : grpc::Status::OK);
      return;
    }
    boost::asio::post(service_.request_pool_, [this] { AnswerUpdate(); });
  }

  void OnWriteDone(bool ok) override {
    stall_watch_->watched_write = 0;
    if (!ok) {
      FinishWith(stall_watch_->stalled
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
            "follow: the client read nothing for " + FormatSeconds(stall_seconds_) +
                " s (follow_stall_seconds); reconnect and list held_regions to resume"};
  }

  static std::string FormatSeconds(double seconds) {
    std::string text = std::to_string(seconds);
    text.erase(text.find_last_not_of('0') + 1);
    if (text.back() == '.') text.pop_back();
    return text;
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
    StatusOr<PlanePoints> in_view = service_.engine_.Points(world_, update.viewport);
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
      AppendPoints(chunk.points, 0, chunk.points.ids.size(), *message.mutable_points());
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
      ResolvedWorld resolved;
      if (grpc::Status status = service_.worlds_.Resolve(request_, resolved); !status.ok()) {
        return status;
      }
      world_ = resolved.world;
      log_.set_world(world_.Describe());
      tracker_.emplace(world_);
      prefetch_.emplace(service_.engine_, service_.request_pool_, world_);
    } else if (request_.world_choice_case() != v1::FollowRequest::WORLD_CHOICE_NOT_SET) {
      return {grpc::StatusCode::INVALID_ARGUMENT,
              "world: set only in the first message of a Follow call (world or world_name)"};
    }
    if (!request_.has_viewport()) {
      return {grpc::StatusCode::INVALID_ARGUMENT,
              "viewport: required, the half-open rectangle [x0, x1) x [y0, y1)"};
    }
    log_.set_rect(RectFromMessage(request_.viewport()));
    return ToGrpcStatus(ValidateViewportUpdate(world_, UpdateFromMessage(request_),
                                               service_.config_.max_follow_area));
  }

  void WriteNextOrRead() {
    if (next_message_ == answer_.size()) {
      StartRead(&request_);
      return;
    }
    const v1::FollowResponse& response = answer_[next_message_++];
    const uint64_t write = ++writes_started_;
    stall_watch_->watched_write = write;
    // A fresh alarm per write: the previous one has fired or been cancelled.
    stall_alarm_ = std::make_unique<grpc::Alarm>();
    stall_alarm_->Set(std::chrono::system_clock::now() +
                          std::chrono::duration_cast<std::chrono::system_clock::duration>(
                              std::chrono::duration<double>(stall_seconds_)),
                      [watch = stall_watch_, write](bool fired) {
                        if (fired && watch->watched_write == write) Stall(*watch);
                      });
    StartWrite(&response);
  }

  // The pending write has not completed in time: the client stopped
  // reading. Cancelling with our status sends it in the trailers (headers
  // are not flow-controlled, so they pass the full window); the pending
  // write then fails and OnWriteDone finishes the call. Should the write
  // complete in the same instant, the call still ends: it was that slow.
  static void Stall(StallWatch& watch) {
    watch.stalled = true;
    grpc_call_cancel_with_status(watch.call, GRPC_STATUS_DEADLINE_EXCEEDED, watch.message.c_str(),
                                 nullptr);
  }

  ScallopService& service_;
  grpc::CallbackServerContext* context_;
  const double stall_seconds_;
  World world_;
  std::optional<ViewportTracker> tracker_;  // set by the first update
  std::optional<FollowPrefetch> prefetch_;  // set by the first update
  v1::FollowRequest request_;               // the update being read or answered
  std::vector<v1::FollowResponse> answer_;  // the messages of the current answer
  size_t next_message_ = 0;
  uint64_t writes_started_ = 0;
  std::shared_ptr<StallWatch> stall_watch_;
  std::unique_ptr<grpc::Alarm> stall_alarm_;
};

grpc::ServerBidiReactor<v1::FollowRequest, v1::FollowResponse>* ScallopService::Follow(
    grpc::CallbackServerContext* context) {
  return new FollowReactor(*this, context);
}

}  // namespace scallop::server
