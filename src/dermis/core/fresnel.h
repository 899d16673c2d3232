// Fresnel reflectance of smooth interfaces, its first moment, and the specular
// directions: the one implementation, shared by the renderer (materials/, in float),
// the random walk (sss/walk/) and the half-space simulator (sss/halfspace/, in double).
//
// Signed-cosine convention. fresnel_dielectric(cos_i, eta) takes the cosine of the
// incident direction with the normal n and eta = (index on the side n points away from)
// / (index on the side n points to), e.g. inside over outside for an outward normal.
// cos_i > 0: light arrives from the side n points to and eta is n_transmitted /
// n_incident (the half-space simulator's convention: it passes cos_i in [0, 1] and the
// relative index of the side it arrives from). cos_i < 0: light arrives from the other
// side; the relative index is then 1 / eta. |cos_i| is clamped to 1.
#pragma once

#include <algorithm>
#include <cmath>
#include <concepts>
#include <optional>

#include "dermis/core/rgb.h"
#include "dermis/core/vec.h"

namespace dermis {

// Unpolarised Fresnel reflectance of a dielectric interface (Born & Wolf, Principles of
// Optics, 7th ed. 1999, sec. 1.5.2: R = (r_s^2 + r_p^2) / 2). Returns 1 under total
// internal reflection. Float and double; see the convention above.
template <std::floating_point T>
inline T fresnel_dielectric(T cos_i, T eta) {
  cos_i = std::clamp(cos_i, T(-1), T(1));
  if (cos_i < 0) {
    eta = 1 / eta;
    cos_i = -cos_i;
  }
  const T sin2_t = (1 - cos_i * cos_i) / (eta * eta);  // Snell's law
  if (sin2_t >= 1) return 1;                           // total internal reflection
  const T cos_t = std::sqrt(1 - sin2_t);
  // Born & Wolf 1999, sec. 1.5.2: amplitude ratios for s (perpendicular) and p (parallel).
  const T r_s = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const T r_p = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return T(0.5) * (r_s * r_s + r_p * r_p);
}

// The renderer's float signature: also lets mixed arguments (an int or a double
// literal beside a float) resolve to the float template.
inline float fresnel_dielectric(float cos_i, float eta) { return fresnel_dielectric<float>(cos_i, eta); }

// First Fresnel moment FM1(eta) = int_0^1 F(mu, eta) mu dmu (Jensen et al. 2001, sec. 2.4;
// d'Eon & Irving 2011, eq. 7), for light arriving from the side of relative index eta
// (mu = cos_i > 0 in the convention above). Gauss-Legendre (64 nodes) on [mu_c, 1] after
// the substitution mu = mu_c + (1 - mu_c) s^2, which removes F's square-root branch point
// at the critical cosine mu_c = sqrt(1 - eta^2) (eta < 1; below it F = 1 exactly).
double fresnel_moment1(double eta);
// The i-th moment FM_i(eta) = int_0^1 F(mu, eta) mu^i dmu (i >= 0; d'Eon & Irving 2011,
// eq. 7), by the same quadrature; fresnel_moment1(eta) = fresnel_moment(1, eta).
double fresnel_moment(int i, double eta);

// Hemispherical reflectance of the interface for diffuse (Lambertian) incident light:
// 2 FM1(eta) = 2 int_0^1 F(mu, eta) mu dmu.
double fresnel_diffuse_reflectance(double eta);

// Fresnel reflectance of a conductor with complex index eta + i k, per channel
// (exact unpolarised form; Born & Wolf 1999, sec. 14.2). cos_i: |cosine| of incidence.
float fresnel_conductor(float cos_i, float eta, float k);
RGB fresnel_conductor(float cos_i, RGB eta, RGB k);

// Mirror direction of wo (pointing away from the surface) about n (either side).
inline Vec3 reflect(Vec3 wo, Vec3 n) { return -wo + n * (2 * dot(wo, n)); }

// Refracts wo (pointing away from the surface) through the interface with normal n.
// eta: relative index (transmitted side over incident side) for wo on the side n
// points to; for wo on the other side 1 / eta is used (the convention above).
// Returns nothing on total internal reflection.
inline std::optional<Vec3> refract(Vec3 wo, Vec3 n, float eta) {
  float cos_i = dot(n, wo);
  if (cos_i < 0) {
    eta = 1 / eta;
    cos_i = -cos_i;
    n = -n;
  }
  float sin2_t = std::max(0.0f, 1 - cos_i * cos_i) / (eta * eta);  // Snell's law
  if (sin2_t >= 1) return std::nullopt;
  float cos_t = safe_sqrt(1 - sin2_t);
  return -wo / eta + n * (cos_i / eta - cos_t);
}

}  // namespace dermis
