// pbrt-v4's alpha cut-outs ("float alpha" or a float texture on any shape): where alpha
// is 0 the surface is not there for any ray; where it is between 0 and 1 a hit is kept
// with probability alpha, decided by a hash of the ray and the hit, so the same ray
// always gets the same answer (deterministic renders) and the expected visibility is
// alpha (an unbiased stochastic transparency). pbrt-v4 hashes only the ray; the hit's
// distance and primitive are hashed here too, so that two cut-out surfaces along one ray
// are decided independently (pbrt's single number per ray correlates them).
#pragma once

#include <bit>
#include <cstdint>

#include "dermis/core/vec.h"

namespace dermis {

// Looks up a float texture at (u, v): the renderer's textures, seen from the geometry
// layer through a plain function pointer (no virtual call, no include of materials/).
struct AlphaTextureLookup {
  float (*evaluate)(const void* context, int texture, Vec2 uv) = nullptr;
  const void* context = nullptr;
};

namespace alpha_detail {
// SplitMix64's output function (Steele, Lea, Flood, "Fast splittable pseudorandom number
// generators", OOPSLA 2014).
inline uint64_t mix64(uint64_t x) {
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ull;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}
}  // namespace alpha_detail

// A number in [0, 1) that depends only on the ray (o, d), the hit distance t and the
// primitive hit (geometry and primitive ids).
inline float alpha_hash(Vec3 o, Vec3 d, float t, uint32_t geometry, uint32_t primitive) {
  using alpha_detail::mix64;
  uint64_t h = 0x2545f4914f6cdd1dull;
  for (float f : {o.x, o.y, o.z, d.x, d.y, d.z, t}) h = mix64(h ^ std::bit_cast<uint32_t>(f));
  h = mix64(h ^ ((uint64_t(geometry) << 32) | primitive));
  return float(h >> 40) * 0x1p-24f;
}

// True when a hit on a surface of this alpha is cut away (pbrt-v4's rule: alpha >= 1
// never, alpha <= 0 always, otherwise when the hash exceeds alpha).
inline bool alpha_cuts_hit(float alpha, float hash) { return alpha < 1 && (alpha <= 0 || hash >= alpha); }

}  // namespace dermis
