// ScratchPool: working memory lent to whichever thread runs next and taken
// back after, so that calls on many threads reuse a few buffers instead of
// allocating their own each time.
#pragma once

#include <cstddef>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

namespace scallop {

// Thread-safe. Holds at most `max_spare` objects between calls; a T is made
// (default-constructed) when none is spare. O(1) under one mutex.
template <typename T>
class ScratchPool {
 public:
  explicit ScratchPool(size_t max_spare) : max_spare_(max_spare) {}

  std::unique_ptr<T> Take() {
    {
      std::lock_guard lock(mutex_);
      if (!spare_.empty()) {
        std::unique_ptr<T> scratch = std::move(spare_.back());
        spare_.pop_back();
        return scratch;
      }
    }
    return std::make_unique<T>();
  }

  // Keeps `scratch` for a later Take, or frees it when max_spare are kept.
  void Return(std::unique_ptr<T> scratch) {
    std::lock_guard lock(mutex_);
    if (spare_.size() < max_spare_) spare_.push_back(std::move(scratch));
  }

 private:
  const size_t max_spare_;
  std::mutex mutex_;
  std::vector<std::unique_ptr<T>> spare_;
};

}  // namespace scallop
