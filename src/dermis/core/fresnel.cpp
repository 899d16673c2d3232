#include "dermis/core/fresnel.h"

#include <complex>

#include "dermis/core/gauss_legendre.h"

namespace dermis {

double fresnel_moment(int i, double eta) {
  // Below the critical cosine mu_c (only when eta < 1) F = 1: that part is mu_c^(i+1) / (i+1).
  const double mu_c = eta < 1.0 ? std::sqrt(1.0 - eta * eta) : 0.0;
  // On [mu_c, 1], mu = mu_c + (1 - mu_c) s^2, dmu = 2 (1 - mu_c) s ds, makes F(mu)
  // smooth in s (F has a square-root branch point at mu_c).
  static const QuadratureRule rule = gauss_legendre(64, 0.0, 1.0);
  double sum = 0;
  for (size_t j = 0; j < rule.nodes.size(); ++j) {
    const double s = rule.nodes[j];
    const double mu = mu_c + (1.0 - mu_c) * s * s;
    sum += rule.weights[j] * fresnel_dielectric(mu, eta) * std::pow(mu, i) * 2.0 * (1.0 - mu_c) * s;
  }
  return std::pow(mu_c, i + 1) / (i + 1) + sum;
}

double fresnel_moment1(double eta) { return fresnel_moment(1, eta); }

double fresnel_diffuse_reflectance(double eta) { return 2 * fresnel_moment1(eta); }

float fresnel_conductor(float cos_i, float eta, float k) {
  // r_s, r_p from the complex Snell law with n = eta + i k (Born & Wolf 1999, sec. 14.2).
  using C = std::complex<double>;
  double c = std::clamp(double(std::abs(cos_i)), 0.0, 1.0);
  C n(eta, k);
  double sin2 = 1 - c * c;
  C cos_t = std::sqrt(C(1) - C(sin2) / (n * n));
  C r_perp = (C(c) - n * cos_t) / (C(c) + n * cos_t);
  C r_par = (n * C(c) - cos_t) / (n * C(c) + cos_t);
  return float(0.5 * (std::norm(r_perp) + std::norm(r_par)));
}

RGB fresnel_conductor(float cos_i, RGB eta, RGB k) {
  return {fresnel_conductor(cos_i, eta[0], k[0]), fresnel_conductor(cos_i, eta[1], k[1]),
          fresnel_conductor(cos_i, eta[2], k[2])};
}

}  // namespace dermis
