// The classical dipole (Jensen et al. 2001, eqs. 4-5) and its reparameterisation by the
// surface albedo A and mean free path l (Jensen & Buehler 2002, sec. 4.1; METHODS 1.3).
// The radial CDF has a closed form (derived in docs/profiles.md): sampling inverts it
// exactly, starting from a tabulated inverse CDF and polishing with safeguarded Newton.
#pragma once

#include <memory>
#include <vector>

namespace dermis::sss {

// Diffuse Fresnel reflectance F_dr(eta) (Jensen et al. 2001, eq. 5 fit; METHODS 1.3).
double dipole_fresnel_diffuse_reflectance(double eta);
// A_b = (1 + F_dr) / (1 - F_dr) (Jensen et al. 2001, sec. 2.4).
double dipole_boundary_a(double eta);
// Total diffuse reflectance R_d(alpha') = (alpha'/2)(1 + e^{-(4/3) A_b sqrt(3(1-alpha'))}) e^{-sqrt(3(1-alpha'))}
// (Jensen & Buehler 2002, eq. 3). Increasing in alpha' from 0 to 1.
double dipole_total_reflectance(double reduced_albedo, double eta);
// Inverse of dipole_total_reflectance by bisection to 1e-12 in alpha'.
double dipole_reduced_albedo_from_reflectance(double reflectance, double eta);

struct DipoleCoefficients {
  double sigma_a = 0;          // absorption coefficient, 1 / scene units
  double sigma_s_reduced = 0;  // reduced scattering sigma_s (1 - g), 1 / scene units
};

class DipoleProfile {
 public:
  static constexpr double kDefaultKeptFraction = 0.999;

  DipoleProfile() = default;
  // From the medium: sigma_a, sigma_s (1 / scene units), the HG mean cosine g and eta.
  static DipoleProfile from_coefficients(double sigma_a, double sigma_s, double g, double eta,
                                         double kept_fraction = kDefaultKeptFraction);
  // From the surface albedo A in (0, 1), the mean free path l = 1 / sigma'_t (scene units), eta.
  static DipoleProfile from_albedo(double albedo, double mean_free_path, double eta,
                                   double kept_fraction = kDefaultKeptFraction);

  double reduced_albedo() const { return alpha_; }  // alpha' = sigma'_s / sigma'_t
  double mean_free_path() const { return 1 / sigma_t_reduced_; }
  double eta() const { return eta_; }
  DipoleCoefficients coefficients() const { return {sigma_t_reduced_ * (1 - alpha_), sigma_t_reduced_ * alpha_}; }
  double kept_fraction() const { return kept_; }

  // Jensen et al. 2001, eq. 4.
  double eval(double r) const;
  // The exact integral of eval over the plane: (alpha'/2)(e^{-sigma_tr z_r} + e^{-sigma_tr z_v}),
  // which equals dipole_total_reflectance(alpha', eta) (docs/profiles.md).
  double albedo() const { return albedo_; }
  // Energy inside radius r: int_0^r R 2 pi r' dr' in closed form.
  double energy_within(double r) const;
  double r_max() const { return r_max_; }
  double r_max(double energy_fraction) const;
  double sample_radius(double xi) const;
  // 2 pi r R(r) / (A kept) on [0, r_max].
  double pdf_radius(double r) const;

 private:
  DipoleProfile(double alpha, double sigma_t_reduced, double eta, double kept_fraction);
  // Solves energy_within(r) / alpha' = target in [lo, hi] by Newton from `start` (the
  // midpoint if outside), kept inside a shrinking bisection bracket.
  double solve_energy(double target, double lo, double hi, double start) const;

  double alpha_ = 0, sigma_t_reduced_ = 1, eta_ = 1;
  double sigma_tr_ = 0, z_r_ = 1, z_v_ = 1;
  double albedo_ = 0, kept_ = kDefaultKeptFraction, r_max_ = 0;
  double truncated_shape_energy_ = 1;  // energy_within(r_max) / alpha'
  // Inverse CDF at xi = i / 512 (of the truncated distribution): the Newton start.
  std::shared_ptr<const std::vector<double>> inverse_cdf_;
};

}  // namespace dermis::sss
