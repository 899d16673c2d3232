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
// The same from a table of kSurfaceAlbedoNodes exact values uniform in t = (1 - alpha)^(1/4)
// (the nodes closer where A bends most, near alpha = 1), a cubic Hermite between nodes (Fritsch & Carlson 1980, eq. 2),
// slopes by central differences: within 2e-7 of the exact (albedo_inversion_test.cpp), in tens of nanoseconds where the
// exact solves the H-equation (about a millisecond). Made once per process, on first use (about 0.2 s). For the
// profiles made at every entry point (textured or spectral coefficients). alpha is clamped to [0, 1].
inline constexpr int kSurfaceAlbedoNodes = 129;
double surface_albedo_index_matched_tabulated(double single_scattering_albedo);

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
