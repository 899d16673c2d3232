// Henyey-Greenstein phase function in double precision (Henyey & Greenstein 1941),
// for the half-space simulator. The float versions live in core/warp.h.
#pragma once

#include <algorithm>
#include <cmath>

#include "dermis/core/frame.h"
#include "dermis/core/vec.h"

namespace dermis::sss {

// Density over the sphere of directions of the cosine between the propagation
// directions before and after scattering (Henyey & Greenstein 1941):
// p(cos) = (1 - g^2) / (4 pi (1 + g^2 - 2 g cos)^{3/2}).
inline double hg_phase(double cos_theta, double g) {
  const double denom = 1 + g * g - 2 * g * cos_theta;
  return (1 - g * g) / (4 * kPiD * denom * std::sqrt(denom));
}

// Inverts the CDF of the cosine, whose density is 2 pi hg_phase(cos, g) on [-1, 1]
// F(cos) = (1 - g^2)/(2g) [1/sqrt(1 + g^2 - 2 g cos) - 1/(1 + g)] = u solved for cos
// (Henyey & Greenstein 1941; derivation as in Pharr, Jakob & Humphreys 2016, section 15.2.3).
inline double sample_hg_cos(double u, double g) {
  if (std::abs(g) < 1e-5) return 1 - 2 * u;
  const double s = (1 - g * g) / (1 - g + 2 * g * u);
  return std::clamp((1 + g * g - s * s) / (2 * g), -1.0, 1.0);
}

// A new propagation direction at cosine cos_theta to `axis` (unit) and azimuth phi about it.
inline Vec3d direction_about(const Vec3d& axis, double cos_theta, double phi) {
  const double sin_theta = std::sqrt(std::max(0.0, 1 - cos_theta * cos_theta));
  return Framed(axis).to_world({sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta});
}

}  // namespace dermis::sss
