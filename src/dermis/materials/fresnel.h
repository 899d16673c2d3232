// Fresnel reflectance of smooth interfaces, and the specular directions.
#pragma once

#include <cmath>
#include <optional>

#include "dermis/core/rgb.h"
#include "dermis/core/vec.h"

namespace dermis {

// Unpolarised Fresnel reflectance of a dielectric interface (Hecht, Optics, eq. 4.42/4.43
// averaged over polarisations). cos_i: cosine of the incident direction with the normal
// on the side of the incident medium (negative: incident from the other side);
// eta: index of the side the normal points away from over the side it points to.
inline float fresnel_dielectric(float cos_i, float eta) {
  cos_i = std::clamp(cos_i, -1.0f, 1.0f);
  if (cos_i < 0) {
    eta = 1 / eta;
    cos_i = -cos_i;
  }
  float sin2_t = (1 - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1) return 1;  // total internal reflection
  float cos_t = safe_sqrt(1 - sin2_t);
  float r_par = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5f * (r_par * r_par + r_perp * r_perp);
}

// Fresnel reflectance of a conductor with complex index eta + i k, per channel
// (exact unpolarised form; Born & Wolf, Principles of Optics, sec. 14.2).
float fresnel_conductor(float cos_i, float eta, float k);
RGB fresnel_conductor(float cos_i, RGB eta, RGB k);

inline Vec3 reflect(Vec3 wo, Vec3 n) { return -wo + n * (2 * dot(wo, n)); }

// Refracts wo (pointing away from the surface) through the interface with normal n.
// eta: relative index (transmitted side over incident side), taking the side of wo
// into account by the caller. Returns nothing on total internal reflection.
inline std::optional<Vec3> refract(Vec3 wo, Vec3 n, float eta) {
  float cos_i = dot(n, wo);
  if (cos_i < 0) {
    eta = 1 / eta;
    cos_i = -cos_i;
    n = -n;
  }
  float sin2_t = std::max(0.0f, 1 - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1) return std::nullopt;
  float cos_t = safe_sqrt(1 - sin2_t);
  return -wo / eta + n * (cos_i / eta - cos_t);
}

}  // namespace dermis
