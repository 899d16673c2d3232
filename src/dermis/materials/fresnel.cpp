#include "dermis/materials/fresnel.h"

#include <complex>

namespace dermis {

float fresnel_conductor(float cos_i, float eta, float k) {
  // r_s, r_p from the complex Snell law with n = eta + i k (Born & Wolf 14.2).
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
