// Perlin's gradient noise (Perlin 2002, "Improving Noise") and the sums of its octaves
// used by the procedural textures: fractional Brownian motion and turbulence (Perlin
// 1985, "An Image Synthesizer"; Ebert et al., "Texturing and Modeling", ch. 2).
#pragma once

#include "dermis/core/vec.h"

namespace dermis {

// Gradient noise: 0 at every integer lattice point, smooth (C2) everywhere, periodic with
// period 256 along each axis, values in [-sqrt(6), sqrt(6)] by construction (about
// [-1, 1] in practice).
float perlin_noise(Vec3 p);
inline float perlin_noise(float x, float y, float z = 0.5f) { return perlin_noise(Vec3(x, y, z)); }

// pbrt-v4's Noise (util/noise.cpp): the same lattice, permutation and fade, with its own
// gradients for hashes 12-15 (the cloud medium reads it, so that its clouds are pbrt-v4's).
float perlin_noise_pbrt_v4(Vec3 p);

// Sum over `octaves` octaves of omega^i noise(lambda^i p), lambda = 1.99 (pbrt-v4's FBm
// with no filter footprint: every octave is used).
float fbm(Vec3 p, float omega, int octaves);

// The same sum of |noise| plus 0.2 omega^octaves for the octaves beyond the last
// (pbrt-v4's Turbulence with no filter footprint).
float turbulence(Vec3 p, float omega, int octaves);

}  // namespace dermis
