// Follow: a bidirectional stream that follows a moving viewport. Each update
// is read only once the answer to the previous one is written, so a slow
// client holds back the server instead of filling its memory; a write that
// does not complete within follow_stall_seconds, or no update within
// follow_idle_seconds, ends the call with DEADLINE_EXCEEDED (see
// docs/streaming.md for why that code).
#include <algorithm>
#include <boost/asio/post.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "encoded_points.h"
#include "scallop/plane/layer_regions.h"
#include "scallop/plane/viewport_tracker.h"
#include "server/admitted_stream.h"
#include "server/follow_prefetch.h"
#include "server/layer_choice.h"
#include "server/scallop_service.h"
#include "server/stall_timer.h"
#include "server/status_mapping.h"

namespace scallop::server {
namespace {

// The update as layer `layer`'s tracker sees it: the held regions of that layer (-1: a world
// without layers, whose regions are layer 0's in the message).
ViewportUpdate UpdateFromMessage(const v1::FollowRequest& request, int layer = -1) {
  ViewportUpdate update{.viewport = RectFromMessage(request.viewport()),
                        .velocity = {request.velocity_x(), request.velocity_y()},
                        .keep_margin = request.keep_margin()};
  update.held_regions.reserve(static_cast<size_t>(request.held_regions_size()));
  const auto wanted = static_cast<uint32_t>(std::max(layer, 0));
  for (const v1::RegionKey& key : request.held_regions()) {
    if (key.layer() == wanted) update.held_regions.push_back({key.i(), key.j()});
  }
  return update;
}

void SetKey(RegionKey key, int layer, v1::RegionKey& message) {
  message.set_i(key.i);
  message.set_j(key.j);
  if (layer >= 0) message.set_layer(static_cast<uint32_t>(layer));
}

// Whether two requests' layer filters name the same layers in the same order.
bool SameLayers(const v1::FollowRequest& a, const v1::FollowRequest& b) {
  return std::equal(a.layers().begin(), a.layers().end(), b.layers().begin(), b.layers().end());
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
    // One tracker a layer asked for (a layered world's regions are its layers' own), in the
    // layers' order: evictions of every layer, then every layer's new points.
    std::vector<std::pair<RegionKey, int>> evicted;
    std::vector<std::pair<RegionChunk, int>> chunks;
    std::optional<Rect> ahead;
    for (auto& [layer, tracker] : trackers_) {
      const ViewportUpdate update = UpdateFromMessage(request_, layer);
      for (const RegionKey& key : tracker.Update(update)) evicted.emplace_back(key, layer);
      // Generation (if the prefetch did not get there first) happens here,
      // rank by rank in parallel on the engine's pool.
      StatusOr<PlanePoints> in_view =
          shared_.engine.Points(WorldOfLayer(world_, layer), update.viewport);
      if (!in_view.ok()) {
        FinishWith(ToGrpcStatus(in_view.status()));
        return;
      }
      StatusOr<std::vector<RegionChunk>> taken = tracker.TakeUnsent(*in_view);
      if (!taken.ok()) {
        FinishWith(ToGrpcStatus(taken.status()));
        return;
      }
      for (RegionChunk& chunk : *taken) chunks.emplace_back(std::move(chunk), layer);
      ahead = tracker.PrefetchArea(update);
    }
    if (ahead) prefetch_->Request(*ahead);

    // Evictions ride on the first message, the completion flag on the last.
    answer_.clear();
    answer_.resize(std::max<size_t>(chunks.size(), 1));
    for (v1::FollowResponse& response : answer_) response.set_sequence(request_.sequence());
    for (const auto& [key, layer] : evicted) SetKey(key, layer, *answer_.front().add_evicted());
    for (size_t n = 0; n < chunks.size(); ++n) {
      auto& [chunk, layer] = chunks[n];
      v1::PointsChunk& message = *answer_[n].mutable_chunk();
      if (layer >= 0) {
        chunk.points.layers.assign(chunk.points.ids.size(), static_cast<uint8_t>(layer));
        message.set_layer(static_cast<uint32_t>(layer));
      }
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
    if (trackers_.empty()) {
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
      log_.set_world(world_, resolved.description);
      LayerMask mask = kAllLayers;
      if (grpc::Status status = LayerFilterOf(world_, request_.layers(), "layers", mask);
          !status.ok()) {
        return status;
      }
      first_ = request_;
      for (const int layer : LayersAskedFor(world_, mask)) {
        trackers_.emplace_back(layer, ViewportTracker(WorldOfLayer(world_, layer)));
      }
      prefetch_.emplace(shared_.engine, shared_.request_pool, world_);
    } else if (request_.world_choice_case() != v1::FollowRequest::WORLD_CHOICE_NOT_SET) {
      return {grpc::StatusCode::INVALID_ARGUMENT,
              "world: set only in the first message of a Follow call (world or world_name)"};
    } else if (request_.encoding() != v1::POINT_ENCODING_UNSPECIFIED &&
               !SameEncoding(request_.encoding(), encoding_)) {
      return {grpc::StatusCode::INVALID_ARGUMENT,
              "encoding: the first message of a Follow call sets it for the call; later "
              "messages leave it unset or repeat it"};
    } else if (request_.layers_size() != 0 && !SameLayers(request_, first_)) {
      return {grpc::StatusCode::INVALID_ARGUMENT,
              "layers: the first message of a Follow call sets them for the call; later "
              "messages leave them empty or repeat them"};
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
  // One tracker a layer asked for ({-1, ...} for a world without layers); set by the first
  // update, whose layers and encoding hold for the call (first_).
  std::vector<std::pair<int, ViewportTracker>> trackers_;
  v1::FollowRequest first_;
  std::optional<FollowPrefetch> prefetch_;  // set by the first update
  v1::FollowRequest request_;               // the update being read or answered
  std::vector<v1::FollowResponse> answer_;  // the messages of the current answer
  size_t next_message_ = 0;
};

grpc::ServerBidiReactor<v1::FollowRequest, v1::FollowResponse>* ScallopService::Follow(
    grpc::CallbackServerContext* context) {
  return new FollowReactor(shared_, context);
}

}  // namespace scallop::server
