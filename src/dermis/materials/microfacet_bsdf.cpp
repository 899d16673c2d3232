#include "dermis/materials/microfacet_bsdf.h"

#include "dermis/core/fresnel.h"

namespace dermis {

namespace {

// The microfacet normal that scatters wo into wi, with the kind of event.
struct Configuration {
  Vec3 m;
  bool reflection = true;
  float etap = 1;  // index on wi's side over index on wo's side
};

std::optional<Configuration> dielectric_configuration(float eta, Vec3 wo, Vec3 wi) {
  const float co = wo.z, ci = wi.z;
  if (co == 0 || ci == 0) return std::nullopt;
  Configuration c;
  c.reflection = co * ci > 0;
  c.etap = c.reflection ? 1 : (co > 0 ? eta : 1 / eta);
  const auto m = c.reflection ? reflection_half_vector(wo, wi) : refraction_half_vector(wo, wi, c.etap);
  if (!m) return std::nullopt;
  // The chi+ factors of Walter et al. 2007, eqs. 20-21: both directions on the front of
  // the microfacet as seen from their own side of the surface.
  if (dot(wo, *m) * co <= 0 || dot(wi, *m) * ci <= 0) return std::nullopt;
  c.m = *m;
  return c;
}

}  // namespace

float rough_dielectric_eval(const TrowbridgeReitz& d, float eta, Vec3 wo, Vec3 wi) {
  const auto c = dielectric_configuration(eta, wo, wi);
  if (!c) return 0;
  const float F = fresnel_dielectric(dot(wo, c->m), eta);
  const float DG = d.D(c->m) * d.G(wo, wi);
  // Walter et al. 2007, eq. 20, times |cos wi|: D G F / (4 |cos wo| |cos wi|) |cos wi|.
  if (c->reflection) return DG * F / (4 * std::abs(wo.z));
  // Walter et al. 2007, eq. 21 (its eta_o^2 numerator is the radiance scaling 1/etap^2),
  // times |cos wi|: |wi.m| |wo.m| (1 - F) G D / (|cos wo| etap^2 (wi.m + wo.m / etap)^2).
  const float wim = dot(wi, c->m), wom = dot(wo, c->m);
  const float denom = sqr(wim + wom / c->etap) * sqr(c->etap);
  return DG * (1 - F) * std::abs(wim * wom) / (std::abs(wo.z) * denom);
}

float rough_dielectric_pdf(const TrowbridgeReitz& d, float eta, Vec3 wo, Vec3 wi) {
  const auto c = dielectric_configuration(eta, wo, wi);
  if (!c) return 0;
  const float F = fresnel_dielectric(dot(wo, c->m), eta);  // the probability of reflection
  const float pdf_m = d.visible_pdf(wo, c->m);
  if (c->reflection) return pdf_m * reflection_jacobian(wi, c->m) * F;
  return pdf_m * refraction_jacobian(wo, wi, c->m, c->etap) * (1 - F);
}

RGB rough_conductor_eval(const TrowbridgeReitz& d, RGB eta, RGB k, Vec3 wo, Vec3 wi) {
  if (wo.z * wi.z <= 0) return RGB(0);
  if (wo.z < 0) wo = -wo, wi = -wi;  // seen from below: the same surface, mirrored
  const auto m = reflection_half_vector(wo, wi);
  if (!m) return RGB(0);
  // Walter et al. 2007, eq. 20, with the conductor's Fresnel term, times cos wi.
  return fresnel_conductor(dot(wo, *m), eta, k) * (d.D(*m) * d.G(wo, wi) / (4 * wo.z));
}

float rough_conductor_pdf(const TrowbridgeReitz& d, Vec3 wo, Vec3 wi) {
  if (wo.z * wi.z <= 0) return 0;
  if (wo.z < 0) wo = -wo, wi = -wi;
  const auto m = reflection_half_vector(wo, wi);
  if (!m) return 0;
  return d.visible_pdf(wo, *m) * reflection_jacobian(wi, *m);
}

std::optional<MicrofacetSample> rough_conductor_sample(const TrowbridgeReitz& d, Vec3 wo, Vec2 u) {
  if (wo.z == 0) return std::nullopt;
  const bool below = wo.z < 0;
  if (below) wo = -wo;
  MicrofacetSample s;
  s.wi = reflect(wo, d.sample_visible(wo, u));
  if (s.wi.z <= 0) return std::nullopt;  // reflected below the surface: lost
  if (below) s.wi = -s.wi;
  return s;
}

}  // namespace dermis
