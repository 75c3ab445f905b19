// FollowPrefetch: generates the regions ahead of a Follow client's motion on
// the request pool, off the reply's critical path, with at most one prefetch
// queued or running per call so a fast client cannot flood the pool.
#pragma once

#include <boost/asio/thread_pool.hpp>
#include <memory>
#include <mutex>
#include <optional>

#include "scallop/geometry/rect.h"
#include "scallop/plane/plane_engine.h"

namespace scallop::server {

// Thread-safe. The engine and the pool must outlive every prefetch started,
// not only this object: a running prefetch owns its own state.
class FollowPrefetch {
 public:
  // REQUIRES: ValidateWorld(world).ok().
  FollowPrefetch(PlaneEngine& engine, boost::asio::thread_pool& pool, const World& world)
      : engine_(engine), pool_(pool), world_(world), slot_(std::make_shared<Slot>()) {}

  // Asks for `area`'s regions (and their dependencies) to be generated into
  // the engine's cache. If this call's previous prefetch has not started
  // yet, `area` replaces it: only the latest prediction matters. Returns at
  // once; the work is one PlaneEngine::Count of `area` on the pool, whose
  // errors (an area beyond the precision range) are ignored, since a missed
  // prefetch only costs the reply its generation time.
  void Request(const Rect& area);

 private:
  struct Slot {
    std::mutex mutex;
    std::optional<Rect> waiting;  // the next area to prefetch
    bool running = false;         // a job is posted or running
  };

  PlaneEngine& engine_;
  boost::asio::thread_pool& pool_;
  World world_;
  std::shared_ptr<Slot> slot_;
};

}  // namespace scallop::server
