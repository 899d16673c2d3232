#include "dermis/core/microfacet.h"

#include <limits>

#include "dermis/core/fresnel.h"

namespace dermis {

float TrowbridgeReitz::D(Vec3 m) const {
  if (m.z <= 0) return 0;
  // Heitz 2014, eq. 85: 1 / (pi ax ay cos^4 (1 + tan^2 (cos^2 phi / ax^2 + sin^2 phi / ay^2))^2),
  // multiplied through by cos^4 = mz^4.
  const float e = sqr(m.x / ax_) + sqr(m.y / ay_) + sqr(m.z);
  return 1 / (kPi * ax_ * ay_ * e * e);
}

float TrowbridgeReitz::lambda(Vec3 w) const {
  const float z2 = w.z * w.z;
  if (z2 == 0) return std::numeric_limits<float>::infinity();
  // Heitz 2014, eqs. 80 and 86: alpha(phi)^2 tan^2(theta) = (ax^2 wx^2 + ay^2 wy^2) / wz^2.
  const float a2_tan2 = (sqr(ax_ * w.x) + sqr(ay_ * w.y)) / z2;
  return (std::sqrt(1 + a2_tan2) - 1) / 2;
}

float TrowbridgeReitz::visible_pdf(Vec3 w, Vec3 m) const {
  if (w.z < 0) w = -w;
  const float wm = dot(w, m);
  if (w.z == 0 || wm <= 0 || m.z <= 0) return 0;
  return G1(w) * wm * D(m) / w.z;  // Heitz 2018, eq. 1
}

Vec3 TrowbridgeReitz::sample_visible(Vec3 w, Vec2 u) const {
  if (w.z < 0) w = -w;
  // Heitz 2018, sec. 2: in the stretched configuration (alpha = 1) the visible normals
  // are the projection of a uniform disk perpendicular to w onto the hemisphere.
  const Vec3 v = normalize(Vec3(ax_ * w.x, ay_ * w.y, w.z));
  // An orthonormal basis (t1, t2, v), t1 horizontal.
  const float len2 = v.x * v.x + v.y * v.y;
  const Vec3 t1 = len2 > 0 ? Vec3(-v.y, v.x, 0) / std::sqrt(len2) : Vec3(1, 0, 0);
  const Vec3 t2 = cross(v, t1);
  // A uniform point of the unit disk (polar map), the half disk behind the hemisphere's
  // silhouette squeezed onto the visible part: Heitz 2018, listing lines 9-13.
  const float r = std::sqrt(u.x), phi = 2 * kPi * u.y;
  const float p1 = r * std::cos(phi);
  const float s = 0.5f * (1 + v.z);
  const float p2 = (1 - s) * safe_sqrt(1 - p1 * p1) + s * (r * std::sin(phi));
  // Lift onto the hemisphere along v, then undo the stretch (normals transform by the
  // inverse transpose: multiply x, y by alpha).
  const Vec3 n_h = t1 * p1 + t2 * p2 + v * safe_sqrt(1 - p1 * p1 - p2 * p2);
  return normalize(Vec3(ax_ * n_h.x, ay_ * n_h.y, std::max(0.0f, n_h.z)));
}

std::optional<Vec3> reflection_half_vector(Vec3 wo, Vec3 wi) {
  const Vec3 h = wo + wi;  // Walter et al. 2007, eq. 13
  const float len2 = length_squared(h);
  if (len2 == 0) return std::nullopt;
  const Vec3 m = h / std::sqrt(len2);
  return m.z < 0 ? -m : m;
}

std::optional<Vec3> refraction_half_vector(Vec3 wo, Vec3 wi, float etap) {
  const Vec3 h = wo + wi * etap;  // Walter et al. 2007, eq. 16, divided by the index on wo's side
  const float len2 = length_squared(h);
  if (len2 == 0) return std::nullopt;
  const Vec3 m = h / std::sqrt(len2);
  return m.z < 0 ? -m : m;
}

std::optional<MicrofacetSample> rough_dielectric_sample(const TrowbridgeReitz& d, float eta, Vec3 wo, float u_lobe,
                                                        Vec2 u) {
  if (wo.z == 0) return std::nullopt;
  const Vec3 m = d.sample_visible(wo, u);
  const float F = fresnel_dielectric(dot(wo, m), eta);
  MicrofacetSample s;
  if (u_lobe < F) {
    s.wi = reflect(wo, m);
    if (s.wi.z * wo.z <= 0) return std::nullopt;  // reflected below the surface: lost
    return s;
  }
  const auto t = refract(wo, m, eta);               // m faces +z: eta for wo above, 1/eta below
  if (!t || t->z * wo.z >= 0) return std::nullopt;  // refracted back to wo's side: lost
  s.wi = *t;
  s.transmission = true;
  s.etap = wo.z > 0 ? eta : 1 / eta;
  return s;
}

}  // namespace dermis
