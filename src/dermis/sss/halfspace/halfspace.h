// Brute-force Monte Carlo simulation of light transport in a homogeneous semi-infinite
// medium z < 0 below a flat boundary (Krivanek & d'Eon 2014 set-up; METHODS.md
// sections 4 and 6): the ground truth for the diffusion profiles. Light enters at the
// origin; the result is the total diffuse albedo and the radial exit profile R(r).
// The boundary is index-matched, a smooth dielectric, or a rough one: the renderer's
// Trowbridge-Reitz dielectric (core/microfacet.h), sampled as the renderer samples it.
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
  // The light that enters takes a cosine-distributed direction under the boundary (a
  // diffuse transmission, Chiang, Kutz & Burley 2016) instead of its refracted one; its
  // weight is the boundary's transmission as without it.
  bool entry_lambertian = false;
  // Trowbridge-Reitz alphas of a rough dielectric boundary (pbrt-v4's roughness after
  // remapping). Both below kSmoothAlpha (core/microfacet.h): the smooth boundary, exactly
  // as without them (the renderer's rule). Rough, the entry samples the rough dielectric
  // from outside, as the renderer's entry does (reflection is `specular`, transmission
  // enters with the power weight G / G1, a sample reflected below the surface is `lost`),
  // and every boundary hit from inside samples it from inside (refraction leaves,
  // reflection goes on walking; not with exit_matched). Ignored when eta = 1.
  double alpha_x = 0, alpha_y = 0;
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
// specular + albedo + absorbed + truncated_weight + lost = 1.
struct HalfspaceResult {
  double albedo = 0, albedo_stderr = 0;  // left through the boundary after entering
  // Reflected at entry: smooth, the exact Fresnel reflectance (0 if eta = 1, stderr 0);
  // rough, estimated per path.
  double specular = 0, specular_stderr = 0;
  // Entered the medium: 1 - specular (exact) when smooth; rough, estimated per path.
  double entered = 1, entered_stderr = 0;
  // Rough boundary only: lost by the single-scattering microfacet model (a sample
  // reflected below the surface), at entry or at an exit.
  double lost = 0, lost_stderr = 0;
  double absorbed = 0, absorbed_stderr = 0;                  // absorbed in the medium
  double truncated_weight = 0, truncated_weight_stderr = 0;  // stopped at max_collisions
  uint64_t truncated = 0;                                    // number of truncated paths
  double beyond_rmax = 0, beyond_rmax_stderr = 0;            // part of albedo that left at r >= r_max
  // R(r): exit weight per unit area, weight / (N * annulus area), per bin.
  std::vector<double> r_lo, r_hi, R, R_stderr;
  uint64_t paths = 0;
  double mean_collisions = 0;  // scattering events per path
  double seconds = 0;          // wall-clock time of the simulation

  // The same per unit power that entered the medium, the surface albedo A of METHODS.md
  // section 0: albedo / entered. Smooth, entered = 1 - specular is an exact constant;
  // rough, the ratio of two means over the same paths, its standard error by the delta
  // method (the per-path residual exit - A entered).
  double albedo_per_entering() const { return albedo / entered; }
  double albedo_per_entering_stderr() const { return per_entering_stderr; }
  double per_entering_stderr = 0;
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
