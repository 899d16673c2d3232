// Photon beam diffusion (PBD; Habel, Christensen & Jarosz 2013, "Photon Beam Diffusion: A
// Hybrid Monte Carlo Method for Subsurface Scattering"), in the form pbrt-v4 tabulates for
// its `subsurface` material (Pharr, Jakob & Humphreys, Physically Based Rendering 3rd ed.
// 2016, sec. 15.5): the radial profile of a semi-infinite medium lit by a beam entering
// at normal incidence, as the sum of
//   - multiple scattering: dipoles (Grosjean's diffusion coefficient, the extrapolated
//     boundary of d'Eon & Irving 2011) placed along the refracted beam and integrated
//     over its depth, each weighted by Habel et al.'s correction kappa;
//   - single scattering along the beam, seen from the surface point at distance r
//     through the boundary (only the depths below the critical angle).
// Lengths are in mean free paths (sigma_t = 1); the parameters are the single-scattering
// albedo rho = sigma_s / sigma_t, the Henyey-Greenstein g and the relative index eta.
// The integrals over the beam's depth are computed by Gauss-Legendre quadrature (where
// pbrt-v4 uses 100 stratified exponential samples), so the profile is the model's.
#pragma once

#include "dermis/sss/profiles/tabulated.h"

namespace dermis::sss {

class PhotonBeamDiffusion {
 public:
  // rho in [0, 1], g in (-1, 1), eta > 0 (inside over outside).
  PhotonBeamDiffusion(double rho, double g, double eta);

  // The radiant exitance at distance r > 0 (in mean free paths) per unit power entering.
  double multiple(double r) const;  // E_d(r): the dipoles along the beam
  double single(double r) const;    // E_ss(r): single scattering along the beam
  double eval(double r) const { return multiple(r) + single(r); }

  // The exitance of one dipole whose real source lies at depth z_r (PBR 3rd ed. eqs.
  // 15.27-15.29: c_phi phi(r) + c_E E_n(r)), per unit source power; the beam integrand
  // without its source density and kappa. Public for the tests (its integral over the
  // plane has a closed form, plane_exitance).
  double dipole_exitance(double z_r, double r) const;
  double plane_exitance(double z_r) const;

  double reduced_extinction() const { return sigma_tp_; }  // sigma_t' = sigma_a + sigma_s (1 - g)

 private:
  double rho_, g_, eta_;
  double sigma_a_, sigma_tp_, rho_p_;  // sigma_a, sigma_t', rho' = sigma_s' / sigma_t'
  double d_g_, sigma_tr_, z_e_, c_phi_, c_e_;
  double t_crit_per_r_;  // sqrt(eta^2 - 1): the depth below which no single scattering leaves, per unit r
};

// The PBD profiles at sigma_t = 1 indexed by rho, for ProfileTable (tabulated.h): a
// `TabulatedProfile(table, rho, 1 / sigma_t)` is then the profile of the medium
// (sigma_a, sigma_s) and `table.lookup(rho).energy` its effective albedo rho_eff.
ProfileFamily photon_beam_family(double g, double eta);
// The version of the tabulated model: part of the name of the table cached on disk
// (profile_table_io.h). Raise it whenever a change of this file's code changes the
// table's numbers, or the old file would still be read.
inline constexpr int kPhotonBeamTableVersion = 1;

// The table's options: single-scattering albedos uniform in logit over [1e-3, 1 - 1e-5].
ProfileTableOptions photon_beam_table_options();

}  // namespace dermis::sss
