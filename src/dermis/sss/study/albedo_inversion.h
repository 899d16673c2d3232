// From the surface albedo A (total diffuse reflectance per unit power entering, METHODS 0)
// to the single-scattering albedo alpha = sigma_s / sigma_t of a semi-infinite,
// isotropically scattering medium lit at normal incidence (the "searchlight" of
// Christensen & Burley 2015): the parameter the half-space simulator needs.
#pragma once

#include <cstdint>

namespace dermis::sss {

// Index-matched boundary, exact: A(alpha) = 1 - H(1) sqrt(1 - alpha)
// (Chandrasekhar 1950, ch. V; METHODS 6), H solved numerically (chandrasekhar.h).
double surface_albedo_index_matched(double single_scattering_albedo);

// Its inverse, for A in [0, 1]: solves A(alpha) = A in u = sqrt(1 - alpha) (A is smooth
// in u, whereas dA/dalpha is unbounded at alpha = 1) by bisection to |A(u) - A| <= 1e-13
// or an interval of 1e-16 in u. Throws std::invalid_argument outside [0, 1].
double single_scattering_albedo_index_matched(double surface_albedo);

// Any boundary eta (normal incidence), by simulation: solves
// simulate_halfspace(alpha).albedo_per_entering() = A by regula falsi (Illinois) in
// u = sqrt(1 - alpha) with `paths` paths per evaluation (the same seed each time), until
// the residual is within one standard error of the estimate. eta = 1 returns the exact
// inversion above without simulating. Throws std::invalid_argument for bad input.
struct SimulatedInversion {
  double single_scattering_albedo = 0;
  double surface_albedo = 0, surface_albedo_stderr = 0;  // the simulated A at the answer
  int simulations = 0;                                   // simulate_halfspace calls made
};
SimulatedInversion single_scattering_albedo_simulated(double surface_albedo, double eta, uint64_t paths, uint64_t seed);

}  // namespace dermis::sss
