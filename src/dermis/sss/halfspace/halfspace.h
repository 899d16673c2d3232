// Brute-force Monte Carlo simulation of light transport in a homogeneous semi-infinite
// medium z < 0 below a flat boundary (Krivanek & d'Eon 2014 set-up; METHODS.md
// sections 4 and 6): the ground truth for the diffusion profiles. Light enters at the
// origin; the result is the total diffuse albedo and the radial exit profile R(r).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "dermis/sss/halfspace/radial_bins.h"
#include "dermis/sss/halfspace/walk_sampling.h"

namespace dermis::sss {

enum class Incidence {
  Normal,   // collimated along -z (searchlight)
  Angle,    // collimated at polar angle incidence_angle from the normal, in the xz plane
  Diffuse,  // cosine-weighted over the upper hemisphere (Lambertian sky)
};

struct HalfspaceConfig {
  double albedo = 0.5;   // single-scattering albedo sigma_s / sigma_t, in [0, 1]
  double sigma_t = 1.0;  // extinction coefficient; mean free path 1 / sigma_t
  double g = 0.0;        // HG anisotropy, in (-1, 1)
  double eta = 1.0;      // n_medium / n_outside; 1 = index-matched, else a smooth dielectric
  // Refract at entry by eta but leave at the first boundary crossing (the renderer's
  // `diffuse` random-walk boundary, whose exit lobe lets everything out).
  bool exit_matched = false;
  Incidence incidence = Incidence::Normal;
  double incidence_angle = 0.0;  // radians in [0, pi/2), for Incidence::Angle
  uint64_t paths = 100000;
  uint64_t seed = 1;
  RadialBins bins;
  WalkSampling sampling = WalkSampling::Classical;
  // Probability of the Dwivedi-guided strategy in WalkSampling::Mis, in [0, 1]
  // (docs/random-walk.md: the measured default).
  double p_guided = 0.5;
  // Paths still inside after this many collisions are stopped and reported as
  // truncated (their weight in truncated_weight), never silently lost. Only the
  // non-absorbing case alpha = 1 needs it: the return time of the walk has infinite mean.
  uint64_t max_collisions = 10'000'000;
  // Russian roulette below this fraction of the path's initial weight.
  double roulette_threshold = 0.1;
};

// Every energy figure is per unit incident power, mean over paths +- standard error
// sigma / sqrt(N) from the per-path weights. Energy balance (in expectation):
// specular + albedo + absorbed + truncated_weight = 1.
struct HalfspaceResult {
  double albedo = 0, albedo_stderr = 0;          // left through the boundary after entering
  double specular = 0;                           // reflected at entry (exact Fresnel; 0 if eta = 1)
  double absorbed = 0, absorbed_stderr = 0;      // absorbed in the medium
  double truncated_weight = 0, truncated_weight_stderr = 0;  // stopped at max_collisions
  uint64_t truncated = 0;                        // number of truncated paths
  double beyond_rmax = 0, beyond_rmax_stderr = 0;  // part of albedo that left at r >= r_max
  // R(r): exit weight per unit area, weight / (N * annulus area), per bin.
  std::vector<double> r_lo, r_hi, R, R_stderr;
  uint64_t paths = 0;
  double mean_collisions = 0;  // scattering events per path
  double seconds = 0;          // wall-clock time of the simulation

  // The same per unit power that entered the medium (divides by 1 - specular,
  // an exact constant): the surface albedo A of METHODS.md section 0.
  double albedo_per_entering() const { return albedo / (1 - specular); }
  double albedo_per_entering_stderr() const { return albedo_stderr / (1 - specular); }
};

// Throws std::invalid_argument with an actionable message for bad parameters.
void validate(const HalfspaceConfig& config);

// Runs config.paths paths on the current oneTBB arena, in fixed blocks of paths with
// one Rng stream per block, reduced in block order: the result (all but `seconds`)
// depends only on the config, never on the thread count.
HalfspaceResult simulate_halfspace(const HalfspaceConfig& config);

// "normal", "diffuse" or "angle:DEG" (degrees); throws std::invalid_argument otherwise.
void parse_incidence(const std::string& text, Incidence& incidence, double& angle_radians);

}  // namespace dermis::sss
