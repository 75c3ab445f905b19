// StreamPoints: a large rectangle one region at a time. The next chunk is
// computed only when the previous write is done (OnWriteDone), so a slow
// reader holds back the server instead of filling its memory, and a cancelled
// or expired call stops the work at the next chunk. A chunk not taken within
// stream_stall_seconds ends the call (DEADLINE_EXCEEDED), freeing its slot.
#include <boost/asio/post.hpp>

#include "encoded_points.h"
#include "scallop/plane/layer_regions.h"
#include "scallop/plane/query_rect.h"
#include "scallop/plane/region_layout.h"
#include "server/admitted_stream.h"
#include "server/layer_choice.h"
#include "server/scallop_service.h"
#include "server/stall_timer.h"
#include "server/status_mapping.h"

namespace scallop::server {

class StreamPointsReactor final : public AdmittedStream<grpc::ServerWriteReactor<v1::PointsChunk>> {
 public:
  StreamPointsReactor(ServiceContext& shared, grpc::CallbackServerContext* context,
                      const v1::StreamPointsRequest& request)
      : AdmittedStream(shared, "StreamPoints"),
        shared_(shared),
        context_(context),
        stall_seconds_(shared.config.stream_stall_seconds),
        stall_message_(std::make_shared<const std::string>(StallStatus().error_message())),
        timer_(context) {
    if (!Admit(*context, shared.Authorize(*context, request))) return;
    if (grpc::Status status = Prepare(request); !status.ok()) {
      FinishWith(status);
      return;
    }
    ScheduleNextChunk();
  }

  void OnWriteDone(bool ok) override {
    timer_.Disarm();
    if (!ok) {
      FinishWith(timer_.fired()
                     ? StallStatus()
                     : grpc::Status(grpc::StatusCode::CANCELLED, "stream: the client went away"));
      return;
    }
    ScheduleNextChunk();
  }

  void OnDone() override { delete this; }

 private:
  grpc::Status StallStatus() const {
    return {grpc::StatusCode::DEADLINE_EXCEEDED,
            "stream: the client read nothing for " + SecondsText(stall_seconds_) +
                " s (stream_stall_seconds); resume from the last region received"};
  }

  grpc::Status Prepare(const v1::StreamPointsRequest& request) {
    if (grpc::Status status = shared_.ResolveQuery(request, shared_.config.max_stream_area,
                                                   "max_stream_area", log_, world_, rect_);
        !status.ok()) {
      return status;
    }
    StatusOr<PointEncoding> encoding = PointEncodingFromMessage(request.encoding());
    if (!encoding.ok()) return ToGrpcStatus(encoding.status());
    encoding_ = *encoding;
    LayerMask mask = kAllLayers;
    if (grpc::Status status = LayerFilterOf(world_, request.layers(), "layers", mask);
        !status.ok()) {
      return status;
    }
    layers_ = LayersAskedFor(world_, mask);
    StartLayer(0);
    return grpc::Status::OK;
  }

  // The regions of the n-th layer asked for (the world's own without layers).
  void StartLayer(size_t n) {
    part_ = n;
    if (n >= layers_.size()) return;
    range_ = RegionsOverlapping(RegionLayout(WorldOfLayer(world_, layers_[n])), rect_);
    next_ = range_.low;
  }

  void ScheduleNextChunk() {
    boost::asio::post(shared_.request_pool, [this] { WriteNextChunk(); });
  }

  // Regions in the order GetPoints returns them (rows, then columns; a
  // layered world's layer by layer), so the stream's concatenation equals
  // the unary answer. Skips regions with no point inside the rectangle.
  void WriteNextChunk() {
    while (true) {
      if (context_->IsCancelled()) {
        FinishWith({grpc::StatusCode::CANCELLED, "stream: cancelled or past its deadline"});
        return;
      }
      if (part_ < layers_.size() && next_.j > range_.high.j) StartLayer(part_ + 1);
      if (part_ >= layers_.size()) {
        FinishWith(grpc::Status::OK);
        return;
      }
      const int layer = layers_[part_];
      const World& own = WorldOfLayer(world_, layer);
      const RegionLayout layout(own);
      const RegionKey key = next_;
      next_ =
          key.i < range_.high.i ? RegionKey{key.i + 1, key.j} : RegionKey{range_.low.i, key.j + 1};
      const Rect owned = layout.RegionRect(key);
      const Rect part{std::max(rect_.x0, owned.x0), std::max(rect_.y0, owned.y0),
                      std::min(rect_.x1, owned.x1), std::min(rect_.y1, owned.y1)};
      StatusOr<PlanePoints> points = shared_.engine.Points(own, part);
      if (!points.ok()) {
        FinishWith(ToGrpcStatus(points.status()));
        return;
      }
      if (points->ids.empty()) continue;
      if (layer >= 0) points->layers.assign(points->ids.size(), static_cast<uint8_t>(layer));
      chunk_.Clear();
      AppendPoints(*points, 0, points->ids.size(), *chunk_.mutable_points(), world_, encoding_);
      chunk_.set_region_i(key.i);
      chunk_.set_region_j(key.j);
      if (layer >= 0) chunk_.set_layer(static_cast<uint32_t>(layer));
      log_.add_points(static_cast<int64_t>(points->ids.size()));
      timer_.Arm(stall_seconds_, stall_message_);
      StartWrite(&chunk_);
      return;
    }
  }

  ServiceContext& shared_;
  grpc::CallbackServerContext* context_;
  const double stall_seconds_;
  const std::shared_ptr<const std::string> stall_message_;
  StallTimer timer_;  // watches the pending write
  World world_;
  Rect rect_;
  PointEncoding encoding_ = PointEncoding::kPacked;
  std::vector<int> layers_;  // the layers asked for ({-1}: a world without layers)
  size_t part_ = 0;          // the one being streamed: layers_[part_]
  RegionRange range_;        // its regions

  RegionKey next_;
  v1::PointsChunk chunk_;  // the chunk being written; reused, alive until OnWriteDone
};

grpc::ServerWriteReactor<v1::PointsChunk>* ScallopService::StreamPoints(
    grpc::CallbackServerContext* context, const v1::StreamPointsRequest* request) {
  return new StreamPointsReactor(shared_, context, *request);
}

}  // namespace scallop::server
