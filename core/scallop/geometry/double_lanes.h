// Two lanes of doubles, or of their bits, in one SSE2 register (a GCC and
// Clang vector extension): each lane sees the IEEE operations it would see
// in scalar code, in the same order, so it gets the same bits. A3's arcs and
// the nearest lookups compute in them.
#pragma once

#include <cmath>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace scallop {

using Doubles = double __attribute__((vector_size(16)));
using DoubleBits = int64_t __attribute__((vector_size(16)));

// {sqrt(t[0]), sqrt(t[1])}: one packed square root where SSE2 has it (the
// same correctly rounded bits), where std::sqrt gave two, each behind a
// branch that keeps errno for negative inputs (t >= 0 here). Always inlined,
// so that code compiled for another target (the nearest lookups' AVX2 entry)
// never calls it across two ABIs.
[[gnu::always_inline]] inline Doubles SquareRoots(Doubles t) {
#if defined(__SSE2__)
  return _mm_sqrt_pd(t);
#else
  return Doubles{std::sqrt(t[0]), std::sqrt(t[1])};
#endif
}

}  // namespace scallop
