#include "dermis/render/path/subsurface_vertex.h"

#include "dermis/geometry/shading_normal.h"
#include "dermis/materials/bsdf.h"
#include "dermis/materials/fresnel.h"
#include "dermis/render/path/camera_reflection.h"
#include "dermis/render/path/direct_light.h"
#include "dermis/render/path/emission.h"
#include "dermis/render/path/lights_from_inside.h"
#include "dermis/render/path/sampler_regions.h"
#include "dermis/render/path/surface_vertex.h"
#include "dermis/render/path_splitting.h"
#include "dermis/render/russian_roulette.h"
#include "dermis/render/spectral_media.h"
#include "dermis/render/subsurface/object_tracer.h"

namespace dermis {

SubsurfaceVertex::SubsurfaceVertex(PathContext& ctx, PathState& st, const SurfaceHit& hit, const Material& mat, Vec3 wo)
    : ctx_(ctx), st_(st), hit_(hit), mat_(mat), sm_(*ctx.sc.subsurface[mat.subsurface]), wo_(wo) {}

VertexOutcome SubsurfaceVertex::shade() {
  if (!enter()) return outcome_;
  return exit();
}

bool SubsurfaceVertex::enter() {
  const RenderScene& sc = ctx_.sc;
  Sampler& sampler = ctx_.sampler;
  if (dot(wo_, hit_.ng) <= 0) {
    // Reached from inside (thin or open geometry): let the path pass.
    st_.ray.o = offset_ray_origin(hit_.p, hit_.ng, st_.ray.d);
    st_.ray.tmax = kInfiniteDistance;
    outcome_ = VertexOutcome::kContinue;
    return false;
  }
  first_entry_ = st_.camera_chain;
  st_.camera_chain = false;
  const BSDF boundary = sm_.entry_boundary(hit_);
  const float F = fresnel_dielectric(dot(wo_, hit_.ns), sm_.entry_eta);
  if (boundary.is_rough()) {
    // A rough boundary: the rough dielectric sampled. Reflection continues the path, its
    // emission MIS-weighted against light sampling of the reflection lobe here (the
    // transmitted side is the method's: no lights there); transmission enters the method
    // along the sampled direction, the 1/eta^2 radiance factor omitted as for the smooth
    // entry (the exit's cancels it).
    const bool entry_nee = ctx_.sc.switches.rough_glass_nee;
    const Vec3 p_out = offset_ray_origin(hit_.p, hit_.ng, hit_.ng);
    if (entry_nee) {
      st_.L += st_.beta * estimate_direct(sc, p_out, hit_.ng, st_.medium, sampler, ctx_.counters,
                                          ctx_.start.wavelengths, [&](Vec3 wi) {
                                            if (dot(wi, hit_.ng) <= 0 || !shading_side_agrees(hit_, wi))
                                              return std::pair{RGB(0), 0.0f};
                                            return std::pair{bsdf_eval(boundary, wo_, wi), bsdf_pdf(boundary, wo_, wi)};
                                          });
    }
    const float u_lobe = sampler.get1d();
    const auto bs = bsdf_sample(boundary, wo_, u_lobe, sampler.get2d());
    if (!bs || !shading_side_agrees(hit_, bs->wi)) return false;  // kStop
    if (!bs->transmission) {
      st_.beta *= bs->weight;
      // Without light sampling here: emission counts in full.
      st_.after_scatter(Ray{offset_ray_origin(hit_.p, hit_.ng, bs->wi), bs->wi}, bs->pdf, entry_nee ? p_out : hit_.p,
                        hit_.ng, SkyRule::Sampled, !entry_nee);
      if (!st_.beta.is_finite() || st_.beta.is_black()) return false;
      outcome_ = VertexOutcome::kContinue;
      return false;
    }
    st_.beta *= bs->weight * bs->eta_scale;
    refracted_ = bs->wi;
  } else if (at_camera_first_hit(ctx_, st_)) {
    // The camera's first hit is split (camera_reflection.h): reflection and transmission
    // are both followed, weighted F and 1 - F.
    const Vec3 wi = reflect(wo_, hit_.ns);
    const Ray reflected_ray{offset_ray_origin(hit_.p, hit_.ng, wi), wi};
    const bool reflects = F > 0 && shading_side_agrees(hit_, wi);  // else into the surface: no light
    split_camera_reflection(ctx_, st_, reflected_ray, reflects, st_.beta, F, F);
    st_.beta *= 1 - F;
  } else {
    // Reflection with probability F, else transmission (weights F/F, (1 - F)/(1 - F)).
    // In vacuum, where the reflection meets an emitter brighter than twice the mean sky,
    // its emission is added at every entry, weighted F, and a reflected path goes on
    // without it: one sample of F Le + F L_beyond + (1 - F) L_t, unbiased for any rule
    // that looks at Le alone. After a diffuse bounce, a small light's mirror image met
    // with probability F was a firefly 1/F times its term's mean. The rule: against
    // choosing by Fresnel, the variance falls by F (1 - F) Le (Le + 2 L_beyond - 2 L_t),
    // a gain where Le exceeds about twice what enters, a loss for a sky that the
    // transmitted light matches.
    const bool reflect_path = sampler.get1d() < F;
    const Vec3 wi = reflect(wo_, hit_.ns);
    const Ray reflected{offset_ray_origin(hit_.p, hit_.ng, wi), wi};
    const bool reflects = shading_side_agrees(hit_, wi);  // else into the surface: no light
    const bool counted =
        ctx_.sc.switches.reflection_emission && st_.medium < 0 && F > 0 && reflects &&
        add_bright_emission_seen(sc, reflected, st_.beta * F, ctx_.counters, ctx_.start.wavelengths, st_.L);
    if (reflect_path) {
      if (!reflects) return false;
      st_.after_scatter(reflected, F, hit_.p, hit_.ng, SkyRule::Sampled, true);
      st_.emission_counted = counted;
      outcome_ = VertexOutcome::kContinue;
      return false;
    }
  }
  return true;
}

RGB SubsurfaceVertex::irradiance(Vec3 p, Vec3 n, float eta, Sampler& smp) const {
  return transmitted_irradiance(ctx_.sc, p, n, eta, st_.medium, smp, ctx_.counters,
                                sm_.exit_table ? &*sm_.exit_table : nullptr, &ctx_.split_budget);
}

RGB SubsurfaceVertex::interior_albedo(const SurfaceHit& h) const {
  const Material& m = ctx_.sc.materials[ctx_.sc.shapes[h.shape].material];
  if (m.type != Material::Type::Diffuse) return RGB(0);
  const BSDF b = bsdf_at(m, ctx_.sc.textures, h);
  return ctx_.start.wavelengths ? material_bsdf_at_wavelengths(ctx_.sc, m, b, *ctx_.start.wavelengths).albedo
                                : b.albedo;
}

RGB SubsurfaceVertex::light_through(Vec3 p, Vec3 n, const BSDF& b, Vec3 wo_in, Sampler& smp) const {
  if (!ctx_.sc.switches.rough_glass_nee) return RGB(0);
  return estimate_direct(ctx_.sc, offset_ray_origin(p, n, n), n, st_.medium, smp, ctx_.counters, ctx_.start.wavelengths,
                         [&](Vec3 wi) {
                           if (!shading_side_agrees(n, b.n, wi) || dot(wi, n) <= 0) return std::pair{RGB(0), 0.0f};
                           return std::pair{bsdf_eval(b, wo_in, wi), bsdf_pdf(b, wo_in, wi)};
                         });
}

RGB SubsurfaceVertex::light_through_lobe(const SurfaceHit& at, const BSDF& sw, Sampler& smp) const {
  if (exit_light_none_) return RGB(0);
  return estimate_direct(
      ctx_.sc, offset_ray_origin(at.p, at.ng, at.ng), at.ng, st_.medium, smp, ctx_.counters, ctx_.start.wavelengths,
      [&](Vec3 wi) {
        if (!shading_side_agrees(at, wi)) return std::pair{RGB(0), 0.0f};
        return std::pair{bsdf_eval(sw, at.ns, wi), bsdf_pdf(sw, at.ns, wi)};
      },
      exit_sky_);
}

RGB SubsurfaceVertex::exit_light(const SurfaceHit& at, Sampler& smp) const {
  RoughExitTable table_at;  // a textured roughness: the table of the point's alpha
  return light_through_lobe(at, sm_.exit_lobe(at, table_at), smp);
}

void SubsurfaceVertex::go_on_from_exit(const SurfaceHit& at, const BSDF& lobe, const RGB& weight, float divisor,
                                       uint64_t first_dimension) {
  Sampler& sampler = ctx_.sampler;
  const float u_lobe = sampler.get1d();
  const auto b = bsdf_sample(lobe, at.ns, u_lobe, sampler.get2d());
  if (!b || !shading_side_agrees(at, b->wi)) return;
  const RGB beta_k = st_.beta * weight * b->weight / divisor;
  if (!beta_k.is_finite() || beta_k.is_black()) return;
  const Vec3 p_out_k = offset_ray_origin(at.p, at.ng, at.ng);
  PathStart way_on = continuation(ctx_.start, st_.depth, first_dimension, ctx_.split_budget);
  way_on.prev_pdf = b->pdf;
  way_on.prev_p = p_out_k;
  way_on.prev_n = at.ng;
  way_on.prev_sky = exit_sky_;
  st_.L += beta_k * trace_path(ctx_.sc, Ray{p_out_k, b->wi}, st_.medium, sampler, ctx_.counters, way_on);
}

void SubsurfaceVertex::go_on_along(const SubsurfaceExit& e, float divisor, uint64_t first_dimension) {
  const RGB beta_k = st_.beta * e.weight / divisor;
  if (!beta_k.is_finite() || beta_k.is_black()) return;
  // Through a rough boundary whose lights were sampled (light_through): light found along
  // the direction is weighed against those samples, taken from the same point and normal.
  const bool weighed = e.direction_pdf > 0 && ctx_.sc.switches.rough_glass_nee;
  PathStart way_on = continuation(ctx_.start, st_.depth, first_dimension, ctx_.split_budget);
  way_on.prev_specular = !weighed;
  way_on.prev_pdf = e.direction_pdf;
  way_on.prev_p = weighed ? offset_ray_origin(e.hit.p, e.hit.ng, e.hit.ng) : e.hit.p;
  way_on.prev_n = e.hit.ng;
  way_on.prev_sky = SkyRule::Sampled;  // light_through's samples
  way_on.prev_emission_weight = e.emission_weight;
  st_.L += beta_k * trace_path(ctx_.sc, Ray{offset_ray_origin(e.hit.p, e.hit.ng, e.direction), e.direction}, st_.medium,
                               ctx_.sampler, ctx_.counters, way_on);
}

VertexOutcome SubsurfaceVertex::exit() {
  const RenderScene& sc = ctx_.sc;
  Sampler& sampler = ctx_.sampler;
  // The exit sampler draws from its own region; the exit's light and lobe from this block.
  after_exit_ = sampler.dimension();
  sampler.set_dimension(Sampler::region(after_exit_, kSubsurfaceExitRegion), kStratifiedExitDimensions);
  const ObjectTracer tracer(*sc.embree, sc.object_of_shape, hit_, ctx_.counters);
  strategy_ = ctx_.start.subsurface_strategies ? (*ctx_.start.subsurface_strategies)[std::size_t(mat_.subsurface)] : 0;
  // Whether uniform skies are light-sampled at this material's exits (its method's rule,
  // a walk's by its strategy: SubsurfaceMaterial::exit_sky_rule).
  exit_sky_ = sm_.exit_sky_rule(strategy_);
  // Under uniform skies alone that give way at the exits, no light is sampled there: the
  // exits' light samples are skipped (they would choose none).
  exit_light_none_ = exit_sky_ == SkyRule::GivesWay && sc.light_selection.gives_way_leaves_none();
  auto irradiance = [&](Vec3 p, Vec3 n, float eta, Sampler& smp) { return this->irradiance(p, n, eta, smp); };
  auto interior_albedo = [&](const SurfaceHit& h) { return this->interior_albedo(h); };
  auto light_through = [&](Vec3 p, Vec3 n, const BSDF& b, Vec3 wo_in, Sampler& smp) {
    return this->light_through(p, n, b, wo_in, smp);
  };
  auto exit_light = [&](const SurfaceHit& at, Sampler& smp) { return this->exit_light(at, smp); };
  // The lights for walks behind a smooth boundary (subsurface/refracted_light.h).
  auto sample_light = [&](Vec3 y, float u1, float u2, Vec3& w, float& density) {
    return sample_light_from_inside(sc, y, u1, u2, w, density);
  };
  auto light_density = [&](Vec3 y, Vec3 w) { return light_density_from_inside(sc, y, w); };
  auto emission = [&](Vec3 x, Vec3 n, Vec3 w) {
    return emission_seen(sc, Ray{offset_ray_origin(x, n, w), w}, ctx_.counters, ctx_.start.wavelengths);
  };
  const bool offered_inside = lights_offered_inside(sc, st_.medium);
  const std::optional<KeyLight> key = offered_inside ? key_light(sc) : std::nullopt;
  auto key_direction = [&](Vec3 y, Vec3& toward) { return key_light_direction(key, y, toward); };
  const LightsFromInside lights_inside{sample_light, light_density, emission, key_direction};
  // The camera's first entry averages several exits (below): the scene's
  // subsurfacesamples through the exit lobe, or more (a walk with one colour channel per
  // exit, whatever its boundary).
  const int first_entry_exits = first_entry_ ? sm_.first_entry_exits(strategy_, sc.settings.subsurface_samples) : 0;
  SubsurfaceEntry entry{hit_,
                        wo_,
                        tracer,
                        irradiance,
                        interior_albedo,
                        light_through,
                        exit_light,
                        refracted_,
                        strategy_,
                        first_entry_exits > 0 ? 0 : -1,
                        exit_light_none_};
  if (offered_inside) entry.lights_from_inside = &lights_inside;
  entry.wavelengths = ctx_.start.wavelengths;
  // A grid interior (SubsurfaceParams::interior): the walk reads it at the path's colours or
  // wavelengths, its emission included.
  std::optional<GridMediumView> interior;
  if (const int m = sm_.params.interior_medium; m >= 0 && sc.grid_medium_of(m) >= 0) {
    interior = grid_medium_view(sc, m, ctx_.start.wavelengths, true);
    entry.interior = &*interior;
  }
  if (first_entry_ && ctx_.start.subsurface_record && ctx_.start.subsurface_record->material < 0)
    ctx_.start.subsurface_record->material = mat_.subsurface;
  // The probes' exits at the camera's first entry are one stratified sequence of the
  // pixel's samples: exit k of sample i draws Sobol' index K i + k of dimensions of their
  // own (one set per exit count K: Sampler::set_split); a walk's keep their regions
  // (SubsurfaceMaterial::exits_as_one_sequence). Measured: docs/probe-sampling.md, "The
  // exits as one sequence".
  const bool split_exits = first_entry_exits > 1 && sm_.exits_as_one_sequence();
  const uint64_t exits_region =
      split_exits ? Sampler::region(after_exit_, kSplitExitsRegion + uint32_t(first_entry_exits)) : 0;
  if (split_exits) {
    sampler.set_dimension(exits_region, kStratifiedExitDimensions);
    sampler.set_split(0, uint32_t(first_entry_exits));
  }
  SubsurfaceExit ex;
  const bool exited = sample_subsurface_exit(sm_, entry, sampler, ex);
  sampler.set_split(0, 1);
  // Several exits, each from a sampler region of its own, their direct light averaged
  // (each exit's estimate is unbiased, so is their mean); the path goes on from the first
  // (at the camera's first entry from each: sample_more_exits). At the camera's first
  // entry first_entry_exits of them (subsurfacesamples, or more: above): the entry's cost
  // (the camera ray, the reflection split off, the path after the exit) is paid once. At a
  // later entry, as many as path splitting gives the path's throughput (path_splitting.h):
  // a heavy path's exit light split, not its way on.
  const int exits = first_entry_                ? first_entry_exits
                    : !sm_.exits_through_lobe() ? 1
                                                : split_count(st_.beta, sc.settings.split_threshold, ctx_.split_budget);
  if (exits > 1) sample_more_exits(entry, ex, exited, exits, split_exits, exits_region);
  sampler.set_dimension(after_exit_);
  st_.L += st_.beta * ex.gathered;
  if (!exited) {
    if (ex.truncated) ++ctx_.counters.truncated;
    return VertexOutcome::kStop;
  }
  if (ex.kind == SubsurfaceExit::Kind::Emitted) {
    st_.L += st_.beta * ex.radiance;
    return VertexOutcome::kStop;
  }
  st_.beta *= ex.weight;
  if (!st_.beta.is_finite() || st_.beta.is_black()) return VertexOutcome::kStop;
  if (ex.kind == SubsurfaceExit::Kind::Along) {
    // Through a rough boundary whose lights were sampled: light found along the direction
    // is weighed against those samples, taken from the same point and normal.
    const bool weighed = ex.direction_pdf > 0 && ctx_.sc.switches.rough_glass_nee;
    st_.after_scatter(Ray{offset_ray_origin(ex.hit.p, ex.hit.ng, ex.direction), ex.direction}, ex.direction_pdf,
                      weighed ? offset_ray_origin(ex.hit.p, ex.hit.ng, ex.hit.ng) : ex.hit.p, ex.hit.ng,
                      SkyRule::Sampled /* light_through's samples */, !weighed);
    st_.emission_weight = ex.emission_weight;
    return VertexOutcome::kContinue;
  }
  return leave_through_lobe(ex);
}

void SubsurfaceVertex::sample_more_exits(SubsurfaceEntry& entry, SubsurfaceExit& first, bool found_first, int exits,
                                         bool split_exits, uint64_t exits_region) {
  Sampler& sampler = ctx_.sampler;
  RoughExitTable table_at;  // a textured roughness: the table of the point's alpha
  auto exit_estimate = [&](const SubsurfaceExit& e, bool found) {
    RGB est = e.gathered;
    if (found && e.kind == SubsurfaceExit::Kind::ThroughLobe && !e.exit_light_gathered)
      est += e.weight * light_through_lobe(e.hit, sm_.exit_lobe(e.hit, table_at), sampler);
    return est;
  };
  // At the camera's first entry every exit also goes on (continue_all): each of the n ways
  // on carries 1/n of its exit's weight, the first as the path itself, the others as nested
  // paths from their exits (the mean of n unbiased estimates). With the first alone going
  // on with its whole weight, the light its lobe finds by MIS (about half of a uniform
  // sky's) rested on one walk of the n (measured: docs/results/results-rendering.md, "Every exit goes on").
  const bool continue_all = first_entry_;
  RGB sum = exit_estimate(first, found_first);
  for (int k = 1; k < exits; ++k) {
    SubsurfaceExit other;
    if (entry.exit_index >= 0) entry.exit_index = k;
    if (split_exits) {
      sampler.set_dimension(exits_region, kStratifiedExitDimensions);
      sampler.set_split(uint32_t(k), uint32_t(exits));
    } else {
      sampler.set_dimension(Sampler::region(after_exit_, kExtraExitRegion + uint32_t(k)), kStratifiedExitDimensions);
    }
    const bool found = sample_subsurface_exit(sm_, entry, sampler, other);
    sampler.set_split(0, 1);
    sum += exit_estimate(other, found);
    if (!continue_all || !found) continue;
    if (other.kind == SubsurfaceExit::Kind::Along) {
      go_on_along(other, float(exits), Sampler::region(after_exit_, kExtraExitPathRegion + uint32_t(k)));
      continue;
    }
    if (other.kind != SubsurfaceExit::Kind::ThroughLobe) continue;
    sampler.set_dimension(Sampler::region(after_exit_, kExtraExitLobeRegion + uint32_t(k)), kStratifiedExitDimensions);
    go_on_from_exit(other.hit, sm_.exit_lobe(other.hit, table_at), other.weight, float(exits),
                    Sampler::region(after_exit_, kExtraExitPathRegion + uint32_t(k)));
  }
  first.gathered = sum / float(exits);
  first.exit_light_gathered = true;
  if (continue_all) first.weight /= float(exits);
}

VertexOutcome SubsurfaceVertex::leave_through_lobe(const SubsurfaceExit& ex) {
  const RenderScene& sc = ctx_.sc;
  Sampler& sampler = ctx_.sampler;
  // Leave through the exit lobe Sw at the exit point (normalised Fresnel, or the rough
  // boundary's transmittance): its direct light, unless the method gathered it
  // (SubsurfaceExit::exit_light_gathered), and the lobe sampled for the way on.
  RoughExitTable exit_table_here;  // a textured roughness: the table of the exit point's alpha
  const BSDF sw = sm_.exit_lobe(ex.hit, exit_table_here);
  if (!ex.exit_light_gathered) st_.L += st_.beta * light_through_lobe(ex.hit, sw, sampler);
  const Vec3 p_out = offset_ray_origin(ex.hit.p, ex.hit.ng, ex.hit.ng);
  // A heavy path goes on as several copies from the exit (path_splitting.h): this one and
  // n - 1 nested paths, each with its own direction through the lobe, from a sampler
  // region of its own.
  if (const int copies = split_count(st_.beta, sc.settings.split_threshold, ctx_.split_budget); copies > 1) {
    st_.beta /= float(copies);
    const Sampler::Position resume = sampler.position();
    const uint64_t here = resume.dimension;
    for (int k = 1; k < copies; ++k) {
      sampler.set_dimension(Sampler::region(here, kSplitCopyLobeRegion + uint32_t(k)), kStratifiedExitDimensions);
      go_on_from_exit(ex.hit, sw, RGB(1), 1.0f, Sampler::region(here, kSplitCopyPathRegion + uint32_t(k)));
    }
    sampler.restore(resume);
  }
  const float u_exit_lobe = sampler.get1d();
  auto bs = bsdf_sample(sw, ex.hit.ns, u_exit_lobe, sampler.get2d());
  if (!bs || !shading_side_agrees(ex.hit, bs->wi)) return VertexOutcome::kStop;
  st_.beta *= bs->weight;
  st_.after_scatter(Ray{p_out, bs->wi}, bs->pdf, p_out, ex.hit.ng, exit_sky_, false);
  if (!st_.beta.is_finite() || st_.beta.is_black()) return VertexOutcome::kStop;
  if (!survives_roulette(ctx_, st_, kSurfaceRouletteThreshold)) return VertexOutcome::kStop;
  return VertexOutcome::kContinue;
}

}  // namespace dermis
