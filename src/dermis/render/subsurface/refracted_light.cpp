#include "dermis/render/subsurface/refracted_light.h"

#include <cmath>

namespace dermis {

std::optional<Vec3> refracted_out(Vec3 v, Vec3 n, float eta, float* jacobian) {
  const float cos_v = dot(v, n);
  if (!(cos_v > 0)) return std::nullopt;
  const float sin2_w = eta * eta * std::max(0.0f, 1 - cos_v * cos_v);  // Snell: sin w = eta sin v
  if (sin2_w >= 1) return std::nullopt;                                // total internal reflection
  const float cos_w = std::sqrt(1 - sin2_w);
  if (jacobian) *jacobian = eta * eta * cos_v / cos_w;
  return normalize((v - n * cos_v) * eta + n * cos_w);
}

std::optional<Vec3> refracted_in(Vec3 w, Vec3 n, float eta, float* jacobian) {
  const float cos_w = dot(w, n);
  if (!(cos_w > 0)) return std::nullopt;
  const float sin2_v = std::max(0.0f, 1 - cos_w * cos_w) / (eta * eta);  // Snell: sin v = sin w / eta
  const float cos_v = std::sqrt(1 - sin2_v);
  if (jacobian) *jacobian = eta * eta * cos_v / cos_w;
  return normalize((w - n * cos_w) / eta + n * cos_v);
}

bool RefractedLight::sample(Vec3 y, Vec3 n_ref, float u1, float u2, Vec3& v, float& density) const {
  Vec3 w;
  float light_density = 0, jacobian = 0;
  if (!lights_.sample(y, u1, u2, w, light_density) || !(light_density > 0)) return false;
  const std::optional<Vec3> in = refracted_in(w, n_ref, eta_, &jacobian);
  if (!in) return false;  // a light behind the plane: no flight refracts toward it
  v = *in;
  density = light_density * jacobian;  // p(v) = p(w) dw/dv
  return std::isfinite(density) && density > 0;
}

float RefractedLight::density(Vec3 y, Vec3 n_ref, Vec3 v) const {
  float jacobian = 0;
  const std::optional<Vec3> w = refracted_out(v, n_ref, eta_, &jacobian);
  if (!w) return 0;
  return lights_.density(y, *w) * jacobian;
}

float RefractedLight::walk_weight(Vec3 y, Vec3 n_ref, Vec3 v, float phase, float chance) const {
  const float p = density(y, n_ref, v) * chance;
  return phase * phase + p * p > 0 ? phase * phase / (phase * phase + p * p) : 1.0f;  // Veach 1997, eq. 9.13
}

}  // namespace dermis
