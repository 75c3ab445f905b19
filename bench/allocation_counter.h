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

// Adds p's bytes to the count and raises the peak. Returns p.
inline void* Counted(void* p) {
  if (p == nullptr) throw std::bad_alloc();
  const long long now = g_heap_bytes += static_cast<long long>(malloc_usable_size(p));
  long long peak = g_heap_peak.load();
  while (now > peak && !g_heap_peak.compare_exchange_weak(peak, now)) {
  }
  return p;
}

inline void* CountedAllocate(std::size_t size) {
  return Counted(std::malloc(size == 0 ? 1 : size));
}

// For the aligned operator new (over-aligned types, large grids on huge pages).
inline void* CountedAllocateAligned(std::size_t size, std::align_val_t alignment) {
  const auto align = static_cast<std::size_t>(alignment);
  return Counted(std::aligned_alloc(align, (size + align - 1) / align * align));
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
void* operator new(std::size_t size, std::align_val_t alignment) {
  return scallop::bench::CountedAllocateAligned(size, alignment);
}
void* operator new[](std::size_t size, std::align_val_t alignment) {
  return scallop::bench::CountedAllocateAligned(size, alignment);
}
void operator delete(void* p, std::align_val_t) noexcept { scallop::bench::CountedFree(p); }
void operator delete[](void* p, std::align_val_t) noexcept { scallop::bench::CountedFree(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
  scallop::bench::CountedFree(p);
}
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept {
  scallop::bench::CountedFree(p);
}
