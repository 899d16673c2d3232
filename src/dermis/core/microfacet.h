// The anisotropic Trowbridge-Reitz (GGX) microfacet distribution, its Smith masking,
// the sampling of visible normals, the half-vector Jacobians of reflection and
// refraction, and the sampling of a rough dielectric interface. Geometry-free: every
// direction is a unit vector in the local shading frame, z along the macro-surface
// normal, x along the alpha_x axis. In core/ because two layers use it: the rough
// BSDFs (materials/microfacet_bsdf.h) and the half-space simulator's rough boundary
// (sss/halfspace/), which must sample exactly what the renderer samples.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>

#include "dermis/core/vec.h"

namespace dermis {

// Below this alpha a surface is treated as smooth (pbrt-v4's EffectivelySmooth): the
// specular code path is taken and the distribution is never evaluated.
inline constexpr float kSmoothAlpha = 1e-3f;

// pbrt-v4 scenes' "remaproughness" (default true): alpha = sqrt(roughness)
// (pbrt-v4, TrowbridgeReitzDistribution::RoughnessToAlpha); without it alpha = roughness.
inline float roughness_to_alpha(float roughness, bool remap) {
  return remap ? std::sqrt(std::max(roughness, 0.0f)) : std::max(roughness, 0.0f);
}

class TrowbridgeReitz {
 public:
  TrowbridgeReitz(float alpha_x, float alpha_y) : ax_(alpha_x), ay_(alpha_y) {}

  float alpha_x() const { return ax_; }
  float alpha_y() const { return ay_; }
  bool effectively_smooth() const { return std::max(ax_, ay_) < kSmoothAlpha; }

  // Density of microfacet normals m (m.z > 0, else 0) per solid angle, normalised over
  // projected area: int D(m) m.z dm = 1. Trowbridge & Reitz 1975; Walter et al. 2007,
  // eq. 33 (isotropic); anisotropic form of Heitz 2014, "Understanding the Masking-
  // Shadowing Function in Microfacet-Based BRDFs", eq. 85, written as
  // D = 1 / (pi ax ay (mx^2/ax^2 + my^2/ay^2 + mz^2)^2).
  float D(Vec3 m) const;

  // Smith's Lambda: Heitz 2014, eq. 86 with the projected roughness of eq. 80,
  // Lambda(w) = (sqrt(1 + (ax^2 wx^2 + ay^2 wy^2) / wz^2) - 1) / 2. Even in w.
  float lambda(Vec3 w) const;
  // Masking G1(w) = 1 / (1 + Lambda(w)) (Heitz 2014, eq. 43; equals Walter et al. 2007,
  // eq. 34, for the isotropic case).
  float G1(Vec3 w) const { return 1 / (1 + lambda(w)); }
  // Height-correlated masking-shadowing G(wo, wi) = 1 / (1 + Lambda(wo) + Lambda(wi))
  // (Heitz 2014, eq. 99; more accurate than Walter et al. 2007's separable G1 G1, eq. 23).
  float G(Vec3 wo, Vec3 wi) const { return 1 / (1 + lambda(wo) + lambda(wi)); }

  // Distribution of normals visible from w (Heitz 2014, eq. 38; Heitz 2018, eq. 1):
  // D_w(m) = G1(w) max(0, w'.m) D(m) / w'.z with w' = w flipped to the upper hemisphere
  // (a direction below the surface sees the microfacets' back sides). A density over m
  // in the upper hemisphere that integrates to one; the pdf of sample_visible().
  float visible_pdf(Vec3 w, Vec3 m) const;
  // Samples m from D_w (Heitz 2018, "Sampling the GGX Distribution of Visible Normals",
  // JCGT 7(4), sec. 2: stretch w, sample the projected hemisphere, unstretch).
  Vec3 sample_visible(Vec3 w, Vec2 u) const;

 private:
  float ax_, ay_;
};

// Half vector of a reflection wo -> wi, turned to the upper hemisphere (Walter et al.
// 2007, eq. 13). Nothing when wo + wi vanishes.
std::optional<Vec3> reflection_half_vector(Vec3 wo, Vec3 wi);
// Generalised half vector of a refraction between wo and wi, turned to the upper
// hemisphere: m ~ wo + etap wi with etap = (index on wi's side) / (index on wo's side)
// (Walter et al. 2007, eq. 16). Nothing when it vanishes.
std::optional<Vec3> refraction_half_vector(Vec3 wo, Vec3 wi, float etap);

// |d omega_m / d omega_i| for reflection about m: 1 / (4 |wi.m|) (Walter et al. 2007, eq. 14).
inline float reflection_jacobian(Vec3 wi, Vec3 m) { return 1 / (4 * std::abs(dot(wi, m))); }
// |d omega_m / d omega_i| for refraction through m, etap as above:
// |wi.m| / (wi.m + wo.m / etap)^2 (Walter et al. 2007, eq. 17, divided through by eta_i^2).
inline float refraction_jacobian(Vec3 wo, Vec3 wi, Vec3 m, float etap) {
  return std::abs(dot(wi, m)) / sqr(dot(wi, m) + dot(wo, m) / etap);
}

// One scattering by a rough dielectric interface, sampled.
struct MicrofacetSample {
  Vec3 wi;  // local frame
  bool transmission = false;
  float etap = 1;  // transmission: index on wi's side over index on wo's side
};

// Samples the rough dielectric seen from wo (either side; eta: index on the -z side over
// the index on the +z side): m from the normals visible from wo (Heitz 2018), then
// reflection about m with the microfacet's Fresnel reflectance F(wo.m) (u_lobe < F),
// else refraction through m (Walter et al. 2007). Nothing when the sample is
// lost: a reflection below the surface, a refraction back to wo's side. Its density and
// f |cos wi| are rough_dielectric_pdf and _eval (materials/microfacet_bsdf.h); their
// ratio, with the transmitted radiance scaling etap^2 undone, is the power weight
// G(wo, wi) / G1(wo) of either lobe.
std::optional<MicrofacetSample> rough_dielectric_sample(const TrowbridgeReitz& d, float eta, Vec3 wo, float u_lobe,
                                                        Vec2 u);

}  // namespace dermis
