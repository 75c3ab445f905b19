// RegionCache implementation: one mutex, a hash map and an LRU list.
#include "scallop/plane/region_cache.h"

#include "scallop/random/rng.h"

namespace scallop {

size_t RegionCache::KeyHash::operator()(const KeyView& k) const {
  return HashWords({k.world.fingerprint(), static_cast<uint64_t>(k.region.i),
                    static_cast<uint64_t>(k.region.j)});
}

RegionCache::Lookup RegionCache::Acquire(const World& world, RegionKey key) {
  std::lock_guard lock(mutex_);
  auto it = entries_.find(KeyView{world, key});
  if (it != entries_.end()) {
    ++stats_.hits;
    Entry& entry = it->second;
    if (entry.region) {
      lru_.splice(lru_.begin(), lru_, entry.lru);
      return {entry.region, {}, false};
    }
    return {nullptr, entry.future, false};
  }
  ++stats_.misses;
  Entry entry;
  entry.promise = std::make_shared<std::promise<RegionHandle>>();
  entry.future = entry.promise->get_future().share();
  entries_.emplace(Key{world, key}, std::move(entry));
  return {nullptr, {}, true};
}

bool RegionCache::PeekAll(const World& world, std::span<const RegionKey> keys,
                          std::vector<RegionHandle>& regions) {
  regions.clear();
  regions.reserve(keys.size());
  std::lock_guard lock(mutex_);
  for (const RegionKey& key : keys) {
    const auto it = entries_.find(KeyView{world, key});
    if (it == entries_.end() || !it->second.region) {
      regions.clear();
      return false;
    }
    lru_.splice(lru_.begin(), lru_, it->second.lru);
    regions.push_back(it->second.region);
  }
  stats_.hits += static_cast<int64_t>(keys.size());
  return true;
}

void RegionCache::Publish(const World& world, RegionKey key, RegionHandle region) {
  const Key k{world, key};
  std::shared_ptr<std::promise<RegionHandle>> promise;
  {
    std::lock_guard lock(mutex_);
    Entry& entry = entries_.at(k);
    promise = std::move(entry.promise);
    entry.region = region;
    entry.bytes = static_cast<int64_t>(region->Bytes()) + kEntryBookkeepingBytes;
    lru_.push_front(k);
    entry.lru = lru_.begin();
    stats_.bytes += entry.bytes;
    ++stats_.regions;
    EvictOverBudget();
  }
  promise->set_value(std::move(region));
}

void RegionCache::EvictOverBudget() {
  while (stats_.bytes > byte_budget_ && !lru_.empty()) {
    auto it = entries_.find(lru_.back());
    stats_.bytes -= it->second.bytes;
    --stats_.regions;
    ++stats_.evictions;
    entries_.erase(it);
    lru_.pop_back();
  }
}

RegionCacheStats RegionCache::Stats() const {
  std::lock_guard lock(mutex_);
  RegionCacheStats stats = stats_;
  stats.byte_budget = byte_budget_;
  return stats;
}

}  // namespace scallop
