// Warps from the unit square to common domains, each with its density in the
// stated measure (Shirley & Chiu 1997; pbrt-v4 ch. A.5).
#pragma once

#include <cmath>

#include "dermis/core/henyey_greenstein.h"  // HG sampling, for the callers of this header
#include "dermis/core/vec.h"

namespace dermis {

// Concentric map of the square to the unit disk (Shirley & Chiu 1997). Area pdf 1/pi.
inline Vec2 sample_uniform_disk_concentric(Vec2 u) {
  float x = 2 * u.x - 1, y = 2 * u.y - 1;
  if (x == 0 && y == 0) return {0, 0};
  float r, theta;
  if (std::abs(x) > std::abs(y)) {
    r = x;
    theta = (kPi / 4) * (y / x);
  } else {
    r = y;
    theta = kPi / 2 - (kPi / 4) * (x / y);
  }
  return {r * std::cos(theta), r * std::sin(theta)};
}

// Cosine-weighted hemisphere about +z (Malley's method). Solid-angle pdf cos(theta)/pi.
inline Vec3 sample_cosine_hemisphere(Vec2 u) {
  Vec2 d = sample_uniform_disk_concentric(u);
  float z = safe_sqrt(1 - d.x * d.x - d.y * d.y);
  return {d.x, d.y, z};
}
inline float cosine_hemisphere_pdf(float cos_theta) { return std::max(cos_theta, 0.0f) * kInvPi; }

// Uniform direction on the unit sphere. Solid-angle pdf 1/(4 pi).
inline Vec3 sample_uniform_sphere(Vec2 u) {
  float z = 1 - 2 * u.x;
  float r = safe_sqrt(1 - z * z);
  float phi = 2 * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
inline constexpr float uniform_sphere_pdf() { return kInv4Pi; }

// Uniform direction in the cone about +z with cos(theta) >= cos_max. Pdf 1/(2 pi (1 - cos_max)).
inline Vec3 sample_uniform_cone(Vec2 u, float cos_max) {
  float cos_theta = (1 - u.x) + u.x * cos_max;
  float sin_theta = safe_sqrt(1 - cos_theta * cos_theta);
  float phi = 2 * kPi * u.y;
  return {std::cos(phi) * sin_theta, std::sin(phi) * sin_theta, cos_theta};
}
inline float uniform_cone_pdf(float cos_max) { return 1 / (2 * kPi * (1 - cos_max)); }

// Uniform point on a triangle as barycentrics (b0, b1); b2 = 1 - b0 - b1 (Heitz 2019,
// "A Low-Distortion Map Between Triangle and Square"). Area pdf 1/area.
inline Vec2 sample_uniform_triangle(Vec2 u) {
  float b0, b1;
  if (u.x < u.y) {
    b0 = u.x / 2;
    b1 = u.y - b0;
  } else {
    b1 = u.y / 2;
    b0 = u.x - b1;
  }
  return {b0, b1};
}

}  // namespace dermis
