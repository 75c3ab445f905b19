// FollowPrefetch: one job per call drains the latest predicted area.
#include "server/follow_prefetch.h"

#include <boost/asio/post.hpp>

namespace scallop::server {

void FollowPrefetch::Request(const Rect& area) {
  {
    std::lock_guard lock(slot_->mutex);
    slot_->waiting = area;
    if (slot_->running) return;  // the running job takes the new area next
    slot_->running = true;
  }
  // Captures copies, not `this`: the call may end while the job runs.
  boost::asio::post(pool_, [&engine = engine_, world = world_, slot = slot_] {
    while (true) {
      Rect next;
      {
        std::lock_guard lock(slot->mutex);
        if (!slot->waiting) {
          slot->running = false;
          return;
        }
        next = *slot->waiting;
        slot->waiting.reset();
      }
      (void)engine.Count(world, next);
    }
  });
}

}  // namespace scallop::server
