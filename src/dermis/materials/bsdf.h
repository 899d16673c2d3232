// The surface scattering functions: Lambertian reflection, the dielectric and the
// conductor, smooth or rough (Trowbridge-Reitz microfacets, materials/microfacet_bsdf.h),
// Lambertian reflection and transmission (pbrt-v4's diffusetransmission), the coated
// (layered) surfaces (materials/layered_bsdf.h), and the normalised-Fresnel exit lobe of
// the subsurface methods. Evaluated in world
// space about the geometric normal; the rough lobes in the local frame Frame(n). A
// tagged struct with switches: no virtual call per ray.
#pragma once

#include <optional>

#include "dermis/core/microfacet.h"
#include "dermis/core/rgb.h"
#include "dermis/core/vec.h"
#include "dermis/materials/layered_bsdf.h"

namespace dermis {

struct RoughExitTable;  // materials/rough_exit_lobe.h

struct BSDF {
  enum class Type { Diffuse, Dielectric, Conductor, SubsurfaceExit, DiffuseTransmission, Coated };
  Type type = Type::Diffuse;
  Vec3 n;             // unit normal of the surface (either side)
  RGB albedo;         // diffuse reflectance (Diffuse, DiffuseTransmission)
  RGB transmittance;  // DiffuseTransmission: Lambertian transmission to the other side
  float eta = 1.5f;   // dielectric: index inside over outside (the side n points away from)
  RGB cond_eta, cond_k;
  float sw_norm = 1;  // SubsurfaceExit: c = 1 - 2 FM1(eta), see subsurface_exit_normalization()
  // SubsurfaceExit through a rough boundary: T(mu) replaces 1 - Fr, and sw_norm is the
  // table's c (materials/rough_exit_lobe.h). Null: the smooth lobe.
  const RoughExitTable* exit_table = nullptr;
  // Dielectric, Conductor: Trowbridge-Reitz roughness; below kSmoothAlpha (both) the
  // surface is smooth, exactly as before roughness existed. There are no uv tangents
  // yet, so alpha_x runs along Frame(n).s and alpha_y along Frame(n).t (core/frame.h).
  float alpha_x = 0, alpha_y = 0;
  // Coated: the layer stack, and the seed of the random streams its stochastic eval, pdf
  // and sample draw from (each query its own stream, layered_bsdf.h). The integrator sets
  // a fresh seed per path vertex. MIS stays unbiased with these estimates: next-event
  // estimation weighs f_est(wi) L / p_light by w_L = p_light^2 / (p_light^2 + X^2) and a
  // sampled direction weighs its path weight by w_B = X'^2 / (p_light^2 + X'^2), where X
  // and X' are density estimates drawn independently of f_est, of the sampled path and of
  // each other, by the same estimator. Then E[f_est w_L] = f E[w_L(X)], the sampled term
  // has mean f E[w_B(X')], and E[w_L(X)] + E[w_B(X')] = 1 because X and X' are identically
  // distributed: the weights sum to one in expectation, whatever the estimates' error.
  CoatedLayer coat;
  uint64_t seed = 0;

  bool is_rough() const {
    return (type == Type::Dielectric || type == Type::Conductor) && std::max(alpha_x, alpha_y) >= kSmoothAlpha;
  }
  // Smooth dielectric or conductor: a delta lobe that bsdf_eval and bsdf_pdf do not see.
  bool is_specular() const {
    if (type == Type::Coated) return coat.is_specular();
    return (type == Type::Dielectric || type == Type::Conductor) && !is_rough();
  }
};

// The normalised-Fresnel exit lobe of separable BSSRDFs (Jensen et al. 2001; METHODS.md
// sec. 0): Sw(wi) = (1 - Fr(cos theta_i, eta)) / (c pi) on the outside hemisphere of n,
// c = 1 - 2 FM1 with FM1 = integral_0^1 Fr(mu, eta) mu dmu (the first Fresnel moment), so
// that Sw integrates to one against cos theta. FM1 by the Gauss-Legendre quadrature of
// core/fresnel.h (fresnel_moment1), not by a polynomial fit.
// Through a rough boundary, T(cos theta_i) / (c pi) with the rough dielectric's
// transmittance T (materials/rough_exit_lobe.h). Either is sampled cosine-weighted.
float subsurface_exit_normalization(float eta);

struct BSDFSample {
  Vec3 wi;
  RGB weight;     // f |cos wi| / pdf
  float pdf = 0;  // solid angle; for specular lobes the discrete probability of the lobe;
                  // Coated: an independent estimate of bsdf_pdf(wo, wi), for MIS
  bool specular = false;
  bool transmission = false;
  float eta_scale = 1;  // etap^2 after a refraction (for Russian roulette, pbrt-v4 14.1)
};

// f(wo, wi) |cos wi|; zero for specular lobes. wo and wi point away from the surface.
// Transmission through a dielectric carries the radiance scaling 1/etap^2.
RGB bsdf_eval(const BSDF& b, Vec3 wo, Vec3 wi);
// Coated: Monte Carlo estimates (layered_bsdf.h), from the streams of `seed`.
// Solid-angle density of bsdf_sample choosing wi; zero for specular lobes. For the rough
// lobes it integrates to one minus the probability that bsdf_sample returns nothing (a
// microfacet reflection below the surface, a refraction back to wo's side).
float bsdf_pdf(const BSDF& b, Vec3 wo, Vec3 wi);
// u_lobe chooses reflection (u_lobe < F) or transmission of a dielectric: the smooth
// one's F(wo.n), the rough one's F(wo.m) for the sampled microfacet m.
std::optional<BSDFSample> bsdf_sample(const BSDF& b, Vec3 wo, float u_lobe, Vec2 u);

}  // namespace dermis
