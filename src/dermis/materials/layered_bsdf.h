// pbrt-v4's coated materials (coateddiffuse, coatedconductor) as a stochastic layered
// BSDF: a dielectric interface (smooth or rough) over an opaque base (Lambertian, or a
// smooth or rough conductor), with a homogeneous slab of optical thickness `thickness`
// (extinction 1 per unit of thickness, single-scattering `albedo`, Henyey-Greenstein `g`)
// between them. Light that enters is followed through the slab by a random walk in
// directions only: the position-free formulation of Guo, Hasan & Zhao 2018, "Position-
// free Monte Carlo Simulation for Arbitrary Layered BSDFs" (ACM TOG 37(6)), whose layer
// assumption makes the lateral position irrelevant, so that only the height z in the
// slab and the direction are tracked.
//
// The three queries are Monte Carlo estimates driven by a random stream (seeded by the
// caller, core/rng.h):
//  - coated_sample: one random walk, started with the caller's (u_lobe, u), returns the
//    exit direction and its weight f cos / pdf (a product of per-event weights: an
//    unbiased estimate of the path integral, Guo et al. 2018, sec. 5, forward path
//    tracing);
//  - coated_eval: f(wo, wi) |cos wi| by the same walk with next-event estimation: at
//    every scattering inside the slab the walk is connected to the exit direction wi
//    (through the smooth interface along the one refracted direction; through the rough
//    one by two strategies with the power heuristic, the direction the walk samples next
//    and one the interface samples from wi, as pbrt-v4's LayeredBxDF), Guo et al. 2018, sec. 5;
//  - coated_pdf: the density with which coated_sample returns wi, estimated by the same
//    walk and connections with sampling probabilities in place of BSDF values.
// Each is unbiased for its quantity, and each call draws from its own stream. Why the
// integrator's MIS stays unbiased with estimated densities: see bsdf.h (BSDF::seed).
//
// Two-sided as pbrt-v4's coated materials: seen from below, the same stack mirrored.
// Local frame: z along the normal. No allocation.
#pragma once

#include <cstdint>
#include <optional>

#include "dermis/core/rgb.h"
#include "dermis/core/vec.h"

namespace dermis {

struct CoatedLayer {
  enum class Base { Diffuse, Conductor };
  float eta = 1.5f;                                    // interface: index of the coating over the outside
  float interface_alpha_x = 0, interface_alpha_y = 0;  // Trowbridge-Reitz; 0: smooth
  Base base = Base::Diffuse;
  RGB base_reflectance{0.5f, 0.5f, 0.5f};            // Diffuse
  RGB conductor_eta{1, 1, 1}, conductor_k{0, 0, 0};  // Conductor: its own index (over vacuum)
  float base_alpha_x = 0, base_alpha_y = 0;
  float thickness = 0.01f;  // optical thickness of the slab (extinction 1 per unit)
  RGB albedo{0, 0, 0};      // single-scattering albedo of the slab
  float g = 0;              // Henyey-Greenstein asymmetry of the slab
  int max_depth = 10;       // scattering events inside the slab a walk may take
  int n_samples = 1;        // walks averaged by coated_eval and coated_pdf

  // Every path through the stack is a chain of mirror events: a delta BSDF.
  bool is_specular() const;
};

struct CoatedSample {
  Vec3 wi;  // local frame
  RGB weight;
  bool specular = false;  // every event of the walk was a delta event
};

RGB coated_eval(const CoatedLayer& c, Vec3 wo, Vec3 wi, uint64_t seed);
float coated_pdf(const CoatedLayer& c, Vec3 wo, Vec3 wi, uint64_t seed);
std::optional<CoatedSample> coated_sample(const CoatedLayer& c, Vec3 wo, float u_lobe, Vec2 u, uint64_t seed);

}  // namespace dermis
