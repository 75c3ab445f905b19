// Counts the bytes a benchmark binary holds on the heap, so benchmarks can
// report memory per point. Include in exactly one translation unit of a
// benchmark program: it replaces the global operator new and delete.
#pragma once

#include <malloc.h>

#include <atomic>
#include <cstdlib>
#include <new>

namespace scallop::bench {

inline std::atomic<long long> g_heap_bytes{0};
inline std::atomic<long long> g_heap_peak{0};

// Starts a new peak measurement from the bytes held now.
inline void ResetHeapPeak() { g_heap_peak = g_heap_bytes.load(); }
// The most bytes held since ResetHeapPeak, above what was held then.
inline long long HeapPeakSince(long long baseline) { return g_heap_peak.load() - baseline; }
inline long long HeapBytes() { return g_heap_bytes.load(); }

inline void* CountedAllocate(std::size_t size) {
  void* p = std::malloc(size == 0 ? 1 : size);
  if (p == nullptr) throw std::bad_alloc();
  const long long now = g_heap_bytes += static_cast<long long>(malloc_usable_size(p));
  long long peak = g_heap_peak.load();
  while (now > peak && !g_heap_peak.compare_exchange_weak(peak, now)) {
  }
  return p;
}

inline void CountedFree(void* p) {
  if (p == nullptr) return;
  g_heap_bytes -= static_cast<long long>(malloc_usable_size(p));
  std::free(p);
}

}  // namespace scallop::bench

void* operator new(std::size_t size) { return scallop::bench::CountedAllocate(size); }
void* operator new[](std::size_t size) { return scallop::bench::CountedAllocate(size); }
void operator delete(void* p) noexcept { scallop::bench::CountedFree(p); }
void operator delete[](void* p) noexcept { scallop::bench::CountedFree(p); }
void operator delete(void* p, std::size_t) noexcept { scallop::bench::CountedFree(p); }
void operator delete[](void* p, std::size_t) noexcept { scallop::bench::CountedFree(p); }
