// Counter-based random numbers whose bits are fixed by this file alone.
//
// Scallop promises the same points on every machine and build, so it uses no
// std:: distribution (their algorithms are implementation-defined). The stream
// is SplitMix64 (Steele, Lea & Flood 2014): state advances by a fixed odd
// constant and each output is a bijective 64-bit mix of the state. Doubles are
// the top 53 bits scaled by 2^-53, so they lie in [0, 1) exactly.
#pragma once

#include <cstdint>
#include <initializer_list>

namespace scallop {

// The SplitMix64 finaliser: a bijection on 64-bit integers with good avalanche.
constexpr uint64_t Mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// Hashes a sequence of 64-bit words into one seed: h = Mix64(h + w + golden)
// for each word, starting from h = 0. Documented so seeds can be recomputed.
constexpr uint64_t HashWords(std::initializer_list<uint64_t> words) {
  uint64_t h = 0;
  for (uint64_t w : words) h = Mix64(h + w + 0x9e3779b97f4a7c15ULL);
  return h;
}

class Rng {
 public:
  explicit constexpr Rng(uint64_t seed) : state_(seed) {}

  // Next 64 uniformly distributed bits. O(1).
  constexpr uint64_t NextBits() {
    state_ += 0x9e3779b97f4a7c15ULL;
    return Mix64(state_);
  }

  // Uniform double in [0, 1): (bits >> 11) * 2^-53.
  constexpr double Uniform() { return static_cast<double>(NextBits() >> 11) * 0x1.0p-53; }

  // Uniform double in [lo, hi).
  constexpr double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }

  // Uniform integer in [0, n), n > 0, by Lemire's multiply-shift (bias < n / 2^64).
  constexpr uint64_t Below(uint64_t n) {
    __extension__ using Wide = unsigned __int128;
    return static_cast<uint64_t>((static_cast<Wide>(NextBits()) * n) >> 64);
  }

 private:
  uint64_t state_;
};

}  // namespace scallop
