// The Henyey-Greenstein phase function and the sampling of its cosine: the one
// implementation, in float for the renderer's media and in double for the random walk
// and the half-space simulator.
//
// Convention: cos_theta is the cosine between the propagation directions before and
// after scattering (g > 0: forward scattering; the mean of cos_theta is g).
#pragma once

#include <algorithm>
#include <cmath>
#include <concepts>
#include <type_traits>

#include "dermis/core/vec.h"

namespace dermis {

// Density over the sphere of directions (Henyey & Greenstein 1941, eq. 3):
// p(cos) = (1 - g^2) / (4 pi (1 + g^2 - 2 g cos)^{3/2}).
template <std::floating_point T>
inline T henyey_greenstein(T cos_theta, T g) {
  const T denom = 1 + g * g - 2 * g * cos_theta;
  return (1 - g * g) / (4 * T(kPiD) * denom * std::sqrt(denom));
}

// Samples cos_theta by inverting the CDF of its density 2 pi p(cos) on [-1, 1]:
// F(cos) = (1 - g^2)/(2g) [1/sqrt(1 + g^2 - 2 g cos) - 1/(1 + g)] = u solved for cos
// (Henyey & Greenstein 1941; derivation as in Pharr, Jakob & Humphreys 2016, sec. 15.2.3).
// Below |g| = 1e-3 (float) or 1e-5 (double) the inversion cancels catastrophically
// ((1 + g^2 - s^2) / 2g loses about eps / g) and the isotropic 1 - 2u is used instead.
template <std::floating_point T>
inline T sample_henyey_greenstein_cos(T u, T g) {
  constexpr T kIsotropicBelow = std::is_same_v<T, float> ? T(1e-3) : T(1e-5);
  if (std::abs(g) < kIsotropicBelow) return 1 - 2 * u;
  const T s = (1 - g * g) / (1 - g + 2 * g * u);
  return std::clamp((1 + g * g - s * s) / (2 * g), T(-1), T(1));
}

// The renderer's float signatures (mixed float / double arguments resolve to float).
inline float henyey_greenstein(float cos_theta, float g) { return henyey_greenstein<float>(cos_theta, g); }
inline float sample_henyey_greenstein_cos(float u, float g) { return sample_henyey_greenstein_cos<float>(u, g); }

}  // namespace dermis
