// RegionCache implementation: one mutex, a hash map and an LRU list.
#include "scallop/plane/region_cache.h"

#include "scallop/random/rng.h"

namespace scallop {

size_t RegionCache::KeyHash::operator()(const KeyView& k) const {
  return HashWords({k.world.fingerprint(), static_cast<uint64_t>(k.region.i),
                    static_cast<uint64_t>(k.region.j)});
}

size_t RegionCache::BlockHash::operator()(const BlockKeyView& k) const {
  return HashWords(
      {k.world.fingerprint(), static_cast<uint64_t>(k.bi), static_cast<uint64_t>(k.bj)});
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
  Entry& stored = entries_.emplace(Key{world, key}, std::move(entry)).first->second;
  const BlockKeyView block_key = BlockOf(world, key);
  auto block = blocks_.find(block_key);
  if (block == blocks_.end()) {
    block = blocks_.emplace(BlockKey{world, block_key.bi, block_key.bj}, Block{}).first;
    stats_.bytes += kBlockBookkeepingBytes;
  }
  block->second.entries[SlotOf(key)] = &stored;
  ++block->second.used;
  return {nullptr, {}, true};
}

bool RegionCache::PeekAll(const World& world, std::span<const RegionKey> keys,
                          std::vector<RegionHandle>& regions) {
  regions.clear();
  regions.reserve(keys.size());
  // The blocks found so far: a tile's keys come row by row, and a row of a
  // few regions crosses two or three blocks, which the next rows cross again.
  struct Found {
    int64_t bi;
    int64_t bj;
    const Block* block;
  };
  std::array<Found, 9> found;
  size_t found_count = 0;
  std::lock_guard lock(mutex_);
  for (const RegionKey& key : keys) {
    const BlockKeyView block_key = BlockOf(world, key);
    const Block* block = nullptr;
    for (size_t k = 0; k < found_count; ++k) {
      if (found[k].bi == block_key.bi && found[k].bj == block_key.bj) {
        block = found[k].block;
        break;
      }
    }
    if (block == nullptr) {
      const auto it = blocks_.find(block_key);
      if (it != blocks_.end()) {
        block = &it->second;
        found[found_count < found.size() ? found_count++ : found.size() - 1] = {
            block_key.bi, block_key.bj, block};
      }
    }
    Entry* entry = block != nullptr ? block->entries[SlotOf(key)] : nullptr;
    if (entry == nullptr || !entry->region) {
      regions.clear();
      return false;
    }
    lru_.splice(lru_.begin(), lru_, entry->lru);
    regions.push_back(entry->region);
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
    const auto block = blocks_.find(BlockOf(it->first.world, it->first.region));
    block->second.entries[SlotOf(it->first.region)] = nullptr;
    if (--block->second.used == 0) {
      blocks_.erase(block);
      stats_.bytes -= kBlockBookkeepingBytes;
    }
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
