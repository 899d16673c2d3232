// Random numbers: PCG32 (O'Neill 2014, pcg-cpp), one stream per pixel sample so
// that results do not depend on the thread count.
#pragma once

#include <cstdint>
#include <pcg_random.hpp>

namespace dermis {

// SplitMix64 finaliser (Steele et al. 2014): decorrelates structured seeds.
inline uint64_t mix64(uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

class Rng {
 public:
  Rng() : pcg_(0x853c49e6748fea9bull, 0xda3e39cb94b95bdbull) {}
  // A stream determined by (seed, a, b): e.g. (render seed, pixel index, sample index).
  Rng(uint64_t seed, uint64_t a, uint64_t b = 0)
      : pcg_(mix64(seed ^ mix64(a + 0x632be59bd9b4e019ull * (b + 1))), mix64(a) ^ (b << 1)) {}
  // Uniform float in [0, 1).
  float uniform() { return float(pcg_() >> 8) * 0x1p-24f; }
  // Uniform double in [0, 1).
  double uniform_double() {
    uint64_t hi = pcg_(), lo = pcg_();
    return double(((hi << 32) | lo) >> 11) * 0x1p-53;
  }
  uint32_t next_u32() { return pcg_(); }
  // Uniform integer in [0, n).
  uint32_t uniform_int(uint32_t n) { return pcg_(n); }

 private:
  pcg32 pcg_;
};

}  // namespace dermis
