#include "dermis/materials/bsdf.h"

#include "dermis/core/frame.h"
#include "dermis/core/fresnel.h"
#include "dermis/core/rng.h"
#include "dermis/core/warp.h"
#include "dermis/materials/microfacet_bsdf.h"
#include "dermis/materials/rough_exit_lobe.h"

namespace dermis {

float subsurface_exit_normalization(float eta) {
  return float(1 - fresnel_diffuse_reflectance(eta));  // c = 1 - 2 FM1(eta), METHODS.md sec. 0
}

namespace {

// The exit lobe's transmittance toward cos theta_i = mu: 1 - Fr, or the rough table's T.
float exit_transmittance(const BSDF& b, float mu) {
  return b.exit_table ? b.exit_table->at(mu) : 1 - fresnel_dielectric(mu, b.eta);
}

// The rough lobes in the local frame of n (anisotropy axes: Frame(n).s and .t).
RGB rough_eval(const BSDF& b, Vec3 wo, Vec3 wi) {
  const Frame f(b.n);
  const TrowbridgeReitz d(b.alpha_x, b.alpha_y);
  if (b.type == BSDF::Type::Dielectric) return RGB(rough_dielectric_eval(d, b.eta, f.to_local(wo), f.to_local(wi)));
  return rough_conductor_eval(d, b.cond_eta, b.cond_k, f.to_local(wo), f.to_local(wi));
}

float rough_pdf(const BSDF& b, Vec3 wo, Vec3 wi) {
  const Frame f(b.n);
  const TrowbridgeReitz d(b.alpha_x, b.alpha_y);
  if (b.type == BSDF::Type::Dielectric) return rough_dielectric_pdf(d, b.eta, f.to_local(wo), f.to_local(wi));
  return rough_conductor_pdf(d, f.to_local(wo), f.to_local(wi));
}

std::optional<BSDFSample> rough_sample(const BSDF& b, Vec3 wo, float u_lobe, Vec2 u) {
  const Frame f(b.n);
  const TrowbridgeReitz d(b.alpha_x, b.alpha_y);
  const Vec3 wo_local = f.to_local(wo);
  const auto m = b.type == BSDF::Type::Dielectric ? rough_dielectric_sample(d, b.eta, wo_local, u_lobe, u)
                                                  : rough_conductor_sample(d, wo_local, u);
  if (!m) return std::nullopt;
  BSDFSample s;
  s.wi = f.to_world(m->wi);
  // Weight and pdf from eval and pdf themselves, so that they agree exactly.
  s.pdf = rough_pdf(b, wo, s.wi);
  if (!(s.pdf > 0)) return std::nullopt;
  s.weight = rough_eval(b, wo, s.wi) / s.pdf;
  s.transmission = m->transmission;
  s.eta_scale = m->transmission ? m->etap * m->etap : 1;  // as the smooth dielectric (pbrt-v4 14.1)
  return s;
}

// Lambertian reflection and transmission: the lobe chosen in proportion to the largest
// channel of R and of T (pbrt-v4's DiffuseTransmissionBxDF does the same).
float reflection_probability(const BSDF& b) {
  const float r = b.albedo.max(), t = b.transmittance.max();
  return r + t > 0 ? r / (r + t) : 0;
}

// The coated stack in the local frame of n.
RGB coated_eval_world(const BSDF& b, Vec3 wo, Vec3 wi) {
  const Frame f(b.n);
  return coated_eval(b.coat, f.to_local(wo), f.to_local(wi), b.seed);
}

float coated_pdf_world(const BSDF& b, Vec3 wo, Vec3 wi, uint64_t seed) {
  const Frame f(b.n);
  return coated_pdf(b.coat, f.to_local(wo), f.to_local(wi), seed);
}

}  // namespace

RGB bsdf_eval(const BSDF& b, Vec3 wo, Vec3 wi) {
  if (b.is_rough()) return rough_eval(b, wo, wi);
  if (b.type == BSDF::Type::SubsurfaceExit) {
    float ci = dot(wi, b.n);
    if (ci <= 0) return RGB(0);
    return RGB(exit_transmittance(b, ci) / (b.sw_norm * kPi) * ci);
  }
  if (b.type == BSDF::Type::Coated) return coated_eval_world(b, wo, wi);
  float co = dot(wo, b.n), ci = dot(wi, b.n);
  if (b.type == BSDF::Type::DiffuseTransmission) {
    if (co == 0 || ci == 0) return RGB(0);
    return (co * ci > 0 ? b.albedo : b.transmittance) * (std::abs(ci) * kInvPi);  // R/pi, T/pi times |cos|
  }
  if (b.type != BSDF::Type::Diffuse) return RGB(0);
  if (co * ci <= 0) return RGB(0);  // Lambert reflects on the side of wo only
  return b.albedo * (std::abs(ci) * kInvPi);
}

float bsdf_pdf(const BSDF& b, Vec3 wo, Vec3 wi) {
  if (b.is_rough()) return rough_pdf(b, wo, wi);
  if (b.type == BSDF::Type::SubsurfaceExit) return cosine_hemisphere_pdf(dot(wi, b.n));
  // A fresh stream for each density estimate (the seed's pdf stream, layered_bsdf.cpp).
  if (b.type == BSDF::Type::Coated) return coated_pdf_world(b, wo, wi, b.seed);
  float co = dot(wo, b.n), ci = dot(wi, b.n);
  if (b.type == BSDF::Type::DiffuseTransmission) {
    if (co == 0 || ci == 0) return 0;
    const float pr = reflection_probability(b);
    return (co * ci > 0 ? pr : 1 - pr) * cosine_hemisphere_pdf(std::abs(ci));
  }
  if (b.type != BSDF::Type::Diffuse) return 0;
  if (co * ci <= 0) return 0;
  return cosine_hemisphere_pdf(std::abs(ci));
}

std::optional<BSDFSample> bsdf_sample(const BSDF& b, Vec3 wo, float u_lobe, Vec2 u) {
  if (b.is_rough()) return rough_sample(b, wo, u_lobe, u);
  BSDFSample s;
  if (b.type == BSDF::Type::SubsurfaceExit) {
    // Cosine-weighted about the outward normal; weight (1 - Fr) / c, or T / c.
    Vec3 local = sample_cosine_hemisphere(u);
    if (local.z <= 0) return std::nullopt;
    s.wi = Frame(b.n).to_world(local);
    s.pdf = cosine_hemisphere_pdf(local.z);
    s.weight = RGB(exit_transmittance(b, local.z) / b.sw_norm);
    return s;
  }
  if (b.type == BSDF::Type::Coated) {
    const Frame f(b.n);
    const auto c = coated_sample(b.coat, f.to_local(wo), u_lobe, u, b.seed);
    if (!c) return std::nullopt;
    s.wi = f.to_world(c->wi);
    s.weight = c->weight;
    s.specular = c->specular;
    // For MIS: a density estimate independent of the walk that chose wi (bsdf.h, BSDF::seed).
    s.pdf = c->specular ? 1 : coated_pdf_world(b, wo, s.wi, mix64(b.seed ^ 0x5a3b1e0fu));
    return s;
  }
  float co = dot(wo, b.n);
  if (co == 0) return std::nullopt;
  switch (b.type) {
    case BSDF::Type::DiffuseTransmission: {
      const float pr = reflection_probability(b);
      if (pr <= 0 && b.transmittance.is_black()) return std::nullopt;
      const bool reflect = u_lobe < pr;
      const Vec3 n = (co > 0) == reflect ? b.n : -b.n;
      const Vec3 local = sample_cosine_hemisphere(u);
      if (local.z <= 0) return std::nullopt;
      s.wi = Frame(n).to_world(local);
      s.pdf = (reflect ? pr : 1 - pr) * cosine_hemisphere_pdf(local.z);
      s.weight = (reflect ? b.albedo / pr : b.transmittance / (1 - pr));  // (R/pi) cos / (pr cos/pi)
      s.transmission = !reflect;
      return s;
    }
    case BSDF::Type::Diffuse: {
      Vec3 n = co > 0 ? b.n : -b.n;
      Vec3 local = sample_cosine_hemisphere(u);
      if (local.z <= 0) return std::nullopt;
      s.wi = Frame(n).to_world(local);
      s.pdf = cosine_hemisphere_pdf(local.z);
      s.weight = b.albedo;  // (albedo/pi) cos / (cos/pi)
      return s;
    }
    case BSDF::Type::Dielectric: {
      float F = fresnel_dielectric(co, b.eta);
      s.specular = true;
      if (u_lobe < F) {
        s.wi = reflect(wo, b.n);
        s.pdf = F;
        s.weight = RGB(1);  // F / F
        return s;
      }
      auto wt = refract(wo, b.n, b.eta);
      if (!wt) return std::nullopt;  // cannot happen when F < 1
      float etap = co > 0 ? b.eta : 1 / b.eta;
      s.wi = *wt;
      s.pdf = 1 - F;
      s.transmission = true;
      // Radiance is scaled by 1/etap^2 across the interface (Veach 1997, sec. 5.2).
      s.weight = RGB(1 / (etap * etap));
      s.eta_scale = etap * etap;
      return s;
    }
    case BSDF::Type::Conductor: {
      s.wi = reflect(wo, b.n);
      s.pdf = 1;
      s.specular = true;
      s.weight = fresnel_conductor(std::abs(co), b.cond_eta, b.cond_k);
      return s;
    }
    case BSDF::Type::SubsurfaceExit:
    case BSDF::Type::Coated:  // above
      break;
  }
  return std::nullopt;
}

}  // namespace dermis
