// Dwivedi's zero-variance-based guiding for random walks in a half-space
// (Dwivedi 1982; Krivanek & d'Eon 2014, the seed 004_; METHODS.md section 4).
//
// The importance of a point at depth D below the boundary (the expected score of
// leaving the medium) is approximated by the discrete eigenmode of the half-space
// transport problem, I(D) ~ exp(-kappa sigma_t D), kappa = 1/nu0. Sampling the
// classical kernel times I gives, for isotropic scattering,
//   direction cosine u to the principal axis (pointing OUT of the medium):
//     p(u) = (alpha/2) nu0 / (nu0 - u) on [-1, 1], azimuth uniform;
//   free path: exponential with sigma_t' = sigma_t (1 - u/nu0).
#pragma once

#include "dermis/core/rng.h"

namespace dermis::sss {

// nu0, the positive root of 1 = alpha nu0 atanh(1/nu0) (Krivanek & d'Eon 2014, the
// eigenvalue equation), in the forms that stay accurate at both ends:
// nu0 -> infinity ~ 1/sqrt(3 (1 - alpha)) as alpha -> 1, and nu0 -> 1 with
// nu0 - 1 ~ 2 exp(-2/alpha) (below 1e-308 for alpha < 0.0028) as alpha -> 0.
struct DwivediEigenvalue {
  double nu0 = 0;                    // +infinity at alpha = 1
  double inv_nu0 = 0;                // 1/nu0: 0 at alpha = 1
  double log_nu0_minus_one = 0;      // ln(nu0 - 1): finite for every alpha in (0, 1)
  double one_minus_inv_nu0 = 0;      // 1 - 1/nu0 = (nu0 - 1)/nu0, without cancellation
  double log_one_minus_inv_nu0 = 0;  // ln(1 - 1/nu0)
};

// alpha in (0, 1]; throws std::invalid_argument otherwise. Safeguarded Newton in
// y = ln(nu0 - 1) for alpha < 1/2 and in x = 1/nu0 (series for atanh(x)/x - 1 at
// small x) otherwise: relative accuracy near machine precision in the solved variable.
DwivediEigenvalue dwivedi_eigenvalue(double alpha);
inline double dwivedi_nu0(double alpha) { return dwivedi_eigenvalue(alpha).nu0; }

// The guided direction and distance pdfs about a principal axis for one medium,
// parametrised by the decay rate kappa in [0, 1) of the importance per mean free path:
//   p(u) = kappa / ((1 - kappa u) L),  L = ln((1 + kappa)/(1 - kappa)) = 2 atanh(kappa),
//   sigma_t' = sigma_t (1 - kappa u).
// With kappa = 1/nu0(alpha), L = 2/(alpha nu0) by the eigenvalue equation and p(u) is
// the seed's (alpha/2) nu0/(nu0 - u). kappa = 0 is classical isotropic sampling.
class DwivediGuide {
 public:
  DwivediGuide() = default;  // kappa = 0: uniform direction cosine, classical distances
  // Isotropic scattering (g = 0): kappa = 1/nu0(alpha), the seed's pdfs. For g > 0 the
  // similarity relation (alpha* = alpha (1 - g)/(1 - alpha g), sigma_t* = sigma_t
  // (1 - alpha g); Wyman, Patterson & Wilson 1989) gives the anisotropic medium's decay
  // kappa = (1 - alpha g)/nu0(alpha*); for g <= 0 the isotropic kappa = 1/nu0(alpha)
  // is kept (the similarity value can exceed 1 there). The guided pdfs stay isotropic
  // in azimuth and the walk weights carry the HG phase value, so the walk is unbiased
  // for any choice; this one only decides the variance. alpha in [0, 1], g in (-1, 1);
  // alpha below 1e-12 (a non-scattering medium) gives kappa = 0.
  DwivediGuide(double alpha, double g);

  double kappa() const { return kappa_; }
  // Density of the direction cosine u in [-1, 1] (per unit u; divide by 2 pi per steradian).
  double pdf_cos(double u) const;
  // Inverse CDF: u = nu - (nu + 1) ((nu - 1)/(nu + 1))^xi with nu = 1/kappa
  // (Krivanek & d'Eon 2014), written with expm1 so that it is exact for kappa -> 0.
  double sample_cos(double xi) const;
  // sigma_t'/sigma_t = 1 - kappa u, accurate also when kappa and u are both near 1.
  double extinction_scale(double u) const { return one_minus_kappa_ + kappa_ * (1 - u); }
  // p(u) (1 - kappa u) = kappa / L: the guided joint density of (u, s) is
  // sigma_t (kappa/L) exp(-sigma_t' s), free of the singularity of p(u) at u -> nu.
  double kappa_over_L() const { return kappa_over_l_; }

 private:
  void set(double kappa, double one_minus_kappa, double log_one_minus_kappa);

  double kappa_ = 0;
  double one_minus_kappa_ = 1;
  double nu_minus_one_ = 0;  // (1 - kappa)/kappa; +inf for kappa = 0
  double l_ = 0;             // ln((1 + kappa)/(1 - kappa))
  double kappa_over_l_ = 0.5;
};

}  // namespace dermis::sss
