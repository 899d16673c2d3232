#include "dermis/sss/halfspace/fresnel.h"

#include <cmath>

#include "dermis/sss/halfspace/gauss_legendre.h"

namespace dermis::sss {

double fresnel_dielectric(double cos_i, double eta) {
  cos_i = std::clamp(cos_i, 0.0, 1.0);
  const double sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);  // Snell's law
  if (sin2_t >= 1.0) return 1.0;                               // total internal reflection
  const double cos_t = std::sqrt(1.0 - sin2_t);
  // Born & Wolf 1999, section 1.5.2: amplitude ratios for the s (perpendicular) and
  // p (parallel) polarisations with n_i = 1, n_t = eta; unpolarised R = (r_s^2 + r_p^2)/2.
  const double r_s = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const double r_p = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return 0.5 * (r_s * r_s + r_p * r_p);
}

double fresnel_diffuse_reflectance(double eta) {
  // Below the critical cosine mu_c (only when eta < 1) F = 1: that part is mu_c^2.
  const double mu_c = eta < 1.0 ? std::sqrt(1.0 - eta * eta) : 0.0;
  // On [mu_c, 1], mu = mu_c + (1 - mu_c) s^2 makes F(mu) smooth in s (F has a
  // square-root branch point at mu_c).
  static const QuadratureRule rule = gauss_legendre(64, 0.0, 1.0);
  double sum = 0;
  for (size_t j = 0; j < rule.nodes.size(); ++j) {
    const double s = rule.nodes[j];
    const double mu = mu_c + (1.0 - mu_c) * s * s;
    sum += rule.weights[j] * fresnel_dielectric(mu, eta) * mu * 2.0 * (1.0 - mu_c) * s;
  }
  return mu_c * mu_c + 2.0 * sum;
}

bool refract_through_plane(const Vec3d& d, double eta, Vec3d& transmitted) {
  const double sin2_t = (d.x * d.x + d.y * d.y) / (eta * eta);  // Snell's law
  if (sin2_t >= 1.0) return false;
  const double cos_t = std::sqrt(1.0 - sin2_t);
  transmitted = {d.x / eta, d.y / eta, std::copysign(cos_t, d.z)};
  return true;
}

}  // namespace dermis::sss
