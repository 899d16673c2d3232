// The surface scattering functions of the smooth materials: Lambertian
// reflection, a smooth dielectric and a smooth conductor. Evaluated in world
// space about the geometric normal. A tagged struct with switches: no virtual
// call per ray.
#pragma once

#include <optional>

#include "dermis/core/rgb.h"
#include "dermis/core/vec.h"

namespace dermis {

struct BSDF {
  enum class Type { Diffuse, Dielectric, Conductor, SubsurfaceExit };
  Type type = Type::Diffuse;
  Vec3 n;           // unit normal of the surface (either side)
  RGB albedo;       // diffuse reflectance
  float eta = 1.5f; // dielectric: index inside over outside (the side n points away from)
  RGB cond_eta, cond_k;
  float sw_norm = 1;  // SubsurfaceExit: c = 1 - 2 FM1(eta), see subsurface_exit_normalization()

  bool is_specular() const { return type == Type::Dielectric || type == Type::Conductor; }
};

// The normalised-Fresnel exit lobe of separable BSSRDFs (Jensen et al. 2001; METHODS.md
// sec. 0): Sw(wi) = (1 - Fr(cos theta_i, eta)) / (c pi) on the outside hemisphere of n,
// c = 1 - 2 FM1 with FM1 = integral_0^1 Fr(mu, eta) mu dmu (the first Fresnel moment), so
// that Sw integrates to one against cos theta. FM1 by the Gauss-Legendre quadrature of
// core/fresnel.h (fresnel_moment1), not by a polynomial fit.
float subsurface_exit_normalization(float eta);

struct BSDFSample {
  Vec3 wi;
  RGB weight;        // f |cos wi| / pdf
  float pdf = 0;     // solid angle; for specular lobes the discrete probability of the lobe
  bool specular = false;
  bool transmission = false;
  float eta_scale = 1;  // etap^2 after a refraction (for Russian roulette, pbrt-v4 14.1)
};

// f(wo, wi) |cos wi|; zero for specular lobes. wo and wi point away from the surface.
RGB bsdf_eval(const BSDF& b, Vec3 wo, Vec3 wi);
// Solid-angle density of bsdf_sample choosing wi; zero for specular lobes.
float bsdf_pdf(const BSDF& b, Vec3 wo, Vec3 wi);
std::optional<BSDFSample> bsdf_sample(const BSDF& b, Vec3 wo, float u_lobe, Vec2 u);

}  // namespace dermis
