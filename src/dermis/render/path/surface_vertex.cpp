#include "dermis/render/path/surface_vertex.h"

#include "dermis/geometry/shading_normal.h"
#include "dermis/materials/at_wavelengths.h"
#include "dermis/materials/bsdf.h"
#include "dermis/materials/fresnel.h"
#include "dermis/render/path/camera_reflection.h"
#include "dermis/render/path/direct_light.h"
#include "dermis/render/path/emission.h"
#include "dermis/render/path/sampler_regions.h"
#include "dermis/render/russian_roulette.h"
#include "dermis/render/volumetric_texture.h"

namespace dermis {

BSDF material_bsdf_at_wavelengths(const RenderScene& sc, const Material& mat, BSDF bsdf, const SampledWavelengths& w) {
  bsdf = bsdf_at_wavelengths(bsdf, w);
  auto data = [&](int d) { return tabulated_at(sc.spectra[std::size_t(d)], w); };
  // A conductor given as spectra (a named metal, pbrt-v4's default copper): its own data.
  if (mat.cond_eta_data >= 0 && mat.cond_k_data >= 0) {
    const RGB eta = data(mat.cond_eta_data), k = data(mat.cond_k_data);
    if (bsdf.type == BSDF::Type::Conductor) bsdf.cond_eta = eta, bsdf.cond_k = k;
    if (bsdf.type == BSDF::Type::Coated && bsdf.coat.base == CoatedLayer::Base::Conductor)
      bsdf.coat.conductor_eta = eta, bsdf.coat.conductor_k = k;
  }
  // A reflectance or transmittance given as a spectrum (a named spectrum, a file, samples).
  auto clamped = [](RGB v) {  // as bsdf_at clamps scale x R and scale x T
    for (int c = 0; c < 3; ++c) v[c] = std::clamp(v[c], 0.0f, 1.0f);
    return v;
  };
  if (mat.reflectance_data >= 0) {
    if (bsdf.type == BSDF::Type::Diffuse) bsdf.albedo = data(mat.reflectance_data);
    if (bsdf.type == BSDF::Type::DiffuseTransmission) bsdf.albedo = clamped(data(mat.reflectance_data) * mat.scale);
    if (bsdf.type == BSDF::Type::Coated && bsdf.coat.base == CoatedLayer::Base::Diffuse)
      bsdf.coat.base_reflectance = data(mat.reflectance_data);
  }
  if (mat.transmittance_data >= 0 && bsdf.type == BSDF::Type::DiffuseTransmission)
    bsdf.transmittance = clamped(data(mat.transmittance_data) * mat.scale);
  return bsdf;
}

namespace {

// A dielectric whose index depends on the wavelength (dispersion): the path keeps one of its
// wavelengths, chosen uniformly (SampledWavelengths::terminate_secondary, as pbrt-v4's
// DielectricMaterial keeps its hero), and refracts with that wavelength's index. The other
// wavelengths' throughput ends here; what they gathered before no longer counts (the film
// weighs the kept one by the count of wavelengths: unbiased, as the choice is uniform).
void keep_one_wavelength(PathContext& ctx, PathState& st, const Material& mat, BSDF& bsdf) {
  SampledWavelengths& w = *ctx.start.wavelengths;
  if (!w.secondary_terminated()) {
    w.terminate_secondary(ctx.sampler.get1d());
    for (int i = 0; i < kPathWavelengths; ++i)
      if (i != w.kept()) st.beta[i] = 0;
  }
  bsdf.eta = tabulated_at(ctx.sc.spectra[std::size_t(mat.eta_data)], w)[w.kept()];
}

}  // namespace

VertexOutcome shade_surface(PathContext& ctx, PathState& st, const SurfaceHit& hit, const Shape& s, const Material& mat,
                            Vec3 wo) {
  const RenderScene& sc = ctx.sc;
  Sampler& sampler = ctx.sampler;
  BSDF bsdf = bsdf_at(mat, sc.textures, hit);
  if (ctx.start.wavelengths) {
    bsdf = material_bsdf_at_wavelengths(sc, mat, bsdf, *ctx.start.wavelengths);
    if (mat.eta_data >= 0 && bsdf.type == BSDF::Type::Dielectric) keep_one_wavelength(ctx, st, mat, bsdf);
  }
  // The random streams of a layered BSDF's estimates: fresh for every vertex (bsdf.h).
  if (bsdf.type == BSDF::Type::Coated) bsdf.seed = sampler.sample_hash(st.vertex_dimension ^ kCoatedSeedSalt);
  // Shadow rays leave on the side of the light; the medium there is the one the path
  // is in, since Lambertian reflection stays on the side of wo.
  const Vec3 p_out = offset_ray_origin(hit.p, hit.ng, wo);
  const Vec3 surface_n = dot(hit.ng, wo) >= 0 ? hit.ng : -hit.ng;
  // Lights are sampled wherever the BSDF has a density (not at smooth glass or mirrors).
  // EstimatorSwitches::rough_glass_nee off: none at rough glass, whose emission is then found by
  // the sampled direction alone (the estimator before light sampling there; tests).
  const bool rough_glass = bsdf.type == BSDF::Type::Dielectric && bsdf.is_rough();
  const bool nee = !bsdf.is_specular() && (!rough_glass || ctx.sc.switches.rough_glass_nee);
  // Diffuse transmission and rough glass sample the lights on both sides, each from a
  // point and normal on its own side (the medium behind for transmission), each counting
  // only the directions of its side: a direction sampled into either side then meets
  // its emission MIS-weighted against the light sampling of that side (prev_p, prev_n
  // below).
  const bool two_sided_nee = nee && (bsdf.type == BSDF::Type::DiffuseTransmission || rough_glass);
  const Vec3 p_back = two_sided_nee ? offset_ray_origin(hit.p, hit.ng, -wo) : p_out;
  if (nee) {
    st.L += st.beta * estimate_direct(sc, p_out, surface_n, st.medium, sampler, ctx.counters, ctx.start.wavelengths,
                                      [&](Vec3 wi) {
                                        if (two_sided_nee && dot(wi, surface_n) <= 0) return std::pair{RGB(0), 0.0f};
                                        if (!shading_side_agrees(hit, wi)) return std::pair{RGB(0), 0.0f};
                                        return std::pair{bsdf_eval(bsdf, wo, wi), bsdf_pdf(bsdf, wo, wi)};
                                      });
  }
  if (two_sided_nee) {
    const int medium_behind = medium_after_crossing(s, -wo, hit.ng, st.medium);
    st.L += st.beta * estimate_direct(sc, p_back, -surface_n, medium_behind, sampler, ctx.counters,
                                      ctx.start.wavelengths, [&](Vec3 wi) {
                                        if (dot(wi, surface_n) >= 0 || !shading_side_agrees(hit, wi))
                                          return std::pair{RGB(0), 0.0f};
                                        return std::pair{bsdf_eval(bsdf, wo, wi), bsdf_pdf(bsdf, wo, wi)};
                                      });
  }
  float u_lobe = sampler.get1d();
  const Vec2 u_dir = sampler.get2d();
  const bool smooth_glass = bsdf.type == BSDF::Type::Dielectric && bsdf.is_specular();
  bool split = false;  // the camera's first hit on smooth glass: both sides followed
  if (smooth_glass && at_camera_first_hit(ctx, st)) {
    // The reflection is followed with weight F, the transmission below with 1 - F (the
    // sampled lobes' weights are F/F and (1 - F)/(1 - F) times 1/eta^2).
    const float F = fresnel_dielectric(dot(wo, bsdf.n), bsdf.eta);
    if (F > 0 && F < 1) {
      auto reflected = bsdf_sample(bsdf, wo, 0.0f, u_dir);
      if (reflected && !reflected->transmission) {
        const bool reflects = shading_side_agrees(hit, reflected->wi);  // else into the surface: no light
        const Ray reflected_ray{offset_ray_origin(hit.p, hit.ng, reflected->wi), reflected->wi};
        split_camera_reflection(ctx, st, reflected_ray, reflects, st.beta * reflected->weight, F,
                                F * reflected->weight.max());
        st.beta *= 1 - F;
        u_lobe = 1.0f;  // the transmission below (u_lobe >= F)
        split = true;
      }
    }
  }
  // Smooth glass elsewhere, in vacuum: the reflection's emission counted at every hit, as
  // at a subsurface entry (subsurface_vertex.cpp), the reflection then chosen with
  // probability F as before.
  bool reflection_counted = false;
  if (smooth_glass && !split && ctx.sc.switches.reflection_emission && st.medium < 0) {
    const float F = fresnel_dielectric(dot(wo, bsdf.n), bsdf.eta);
    const auto reflected = F > 0 ? bsdf_sample(bsdf, wo, 0.0f, u_dir) : std::nullopt;
    if (reflected && !reflected->transmission && shading_side_agrees(hit, reflected->wi))
      reflection_counted =
          add_bright_emission_seen(sc, Ray{offset_ray_origin(hit.p, hit.ng, reflected->wi), reflected->wi},
                                   st.beta * reflected->weight * F, ctx.counters, ctx.start.wavelengths, st.L);
  }
  auto bs = bsdf_sample(bsdf, wo, u_lobe, u_dir);
  if (!bs || !shading_side_agrees(hit, bs->wi)) return VertexOutcome::kStop;
  st.emission_counted = reflection_counted && !bs->transmission;
  st.beta *= bs->weight;
  st.eta_scale *= bs->eta_scale;
  if (!bs->specular) st.camera_chain = false;
  const bool behind = two_sided_nee && bs->transmission;
  // No light sampling here: emission counts in full.
  st.after_scatter(Ray{offset_ray_origin(hit.p, hit.ng, bs->wi), bs->wi}, bs->pdf, behind ? p_back : p_out,
                   behind ? -surface_n : surface_n, SkyRule::Sampled, bs->specular || !nee);
  if (bs->transmission) {
    const int before = st.medium;
    st.medium = medium_after_crossing(s, bs->wi, hit.ng, st.medium);
    if (const int v = textured_volumetric(sc, st.medium); v >= 0 && st.medium != before) {
      st.entered = volumetric_medium_at(sc, v, hit, st.wavelengths);
      st.entered_medium = st.medium;
    }
  }
  if (!st.beta.is_finite() || st.beta.is_black()) return VertexOutcome::kStop;
  if (!survives_roulette(ctx, st, kSurfaceRouletteThreshold)) return VertexOutcome::kStop;
  return VertexOutcome::kContinue;
}

}  // namespace dermis
