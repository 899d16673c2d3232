#include "dermis/render/integrator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "dermis/core/frame.h"
#include "dermis/core/warp.h"
#include "dermis/geometry/shading_normal.h"
#include "dermis/materials/bsdf.h"
#include "dermis/materials/free_flight.h"
#include "dermis/materials/fresnel.h"
#include "dermis/render/path_splitting.h"
#include "dermis/render/russian_roulette.h"
#include "dermis/render/volumetric_texture.h"

namespace dermis {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr int kMaxInterfaceCrossings = 256;

// Veach 1997, eq. 9.13 (power heuristic, beta = 2).
inline float power_heuristic(float f, float g) {
  if (f == kInf) return 1;
  float f2 = f * f, g2 = g * g;
  return f2 + g2 > 0 ? f2 / (f2 + g2) : 0.0f;
}

inline int medium_after_crossing(const Shape& s, Vec3 dir, Vec3 ng, int current) {
  if (!s.has_medium_interface) return current;
  return dot(dir, ng) > 0 ? s.outside_medium : s.inside_medium;
}

// Direction with cosine `cos_theta` to `axis`, azimuth 2 pi u.
inline Vec3 direction_about(Vec3 axis, float cos_theta, float u) {
  float sin_theta = safe_sqrt(1 - cos_theta * cos_theta);
  float phi = 2 * kPi * u;
  return Frame(axis).to_world({sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta});
}

// Next-event estimation from point p (already offset for surfaces) in `medium`.
// `scatter(wi)` returns f(wo, wi)|cos| (or the phase function) and its sampling pdf.
// n: the unit normal of the hemisphere the scattering at p sees (zero in a medium), for
// the light selection; a path that finds a light by scattering from here weighs itself
// against this estimate with the same (p, n). Takes two dimensions whether or not it
// returns early, so that the dimensions after it do not shift. The light is chosen with the first number of a pair and the
// number, rescaled within the chosen light's share, is reused with the second as the
// light's 2D sample: each light's samples stay stratified (a separate number for the
// choice would scatter them).
template <class Scatter>
RGB estimate_direct_group(const RenderScene& sc, Vec3 p, Vec3 n, int medium, Sampler& sampler, PathCounters& counters,
                          Scatter&& scatter, int group, float* group_importance = nullptr,
                          SkyRule sky = SkyRule::Sampled) {
  const Vec2 u = sampler.get2d();
  float pmf, u_reused = 0;
  const int li = sc.light_selection.sample(u.x, p, n, &pmf, &u_reused, group, group_importance, sky);
  if (li < 0 || pmf <= 0) return RGB(0);
  const Vec2 u_position{u_reused, u.y};
  const Light& light = sc.lights[li];
  LightSample ls;
  if (!light_sample(light, sc.shapes, p, u_position, ls, n) || ls.pdf <= 0) return RGB(0);
  auto [f, scatter_pdf] = scatter(ls.wi);
  if (f.is_black()) return RGB(0);
  float dist = ls.delta && std::isinf(ls.distance) ? kInf : ls.distance * (1 - 1e-4f);
  RGB tr = shadow_transmittance(sc, p, ls.wi, dist, medium, counters);
  if (tr.is_black()) return RGB(0);
  float light_pdf = pmf * ls.pdf;
  float w = ls.delta ? 1.0f : power_heuristic(light_pdf, scatter_pdf);
  return f * tr * ls.L * (w / light_pdf);
}

// The emission `ray` meets at its first surface, or from the lights at infinity where it
// meets none, in full (as after a specular bounce). In vacuum: no transmittance.
RGB emission_seen(const RenderScene& sc, const Ray& ray, PathCounters& counters) {
  SurfaceHit hit;
  counters.count(ray);
  if (!sc.embree->intersect(ray, hit)) {
    RGB Le(0);
    for (int li : sc.infinite_lights) Le += infinite_light_radiance(sc.lights[li], ray.d);
    return Le;
  }
  const Shape& s = sc.shapes[hit.shape];
  if (s.first_light < 0) return RGB(0);
  const int li = s.first_light + (s.type == Shape::Type::Mesh ? hit.prim : 0);
  return area_light_radiance(sc.lights[li], hit.ng, -ray.d);
}

// The mean luminance of the lights at infinity over the sphere of directions.
float mean_sky_luminance(const RenderScene& sc) {
  float sum = 0;
  for (int li : sc.infinite_lights) {
    const Light& l = sc.lights[li];
    sum += l.environment ? l.environment->average_luminance() : l.emission.luminance();
  }
  return sum;
}

// Whether the emission `ray` meets may be brighter than twice the mean sky, known without
// tracing it: only where it may meet a finite emitter (LightSelection's bounds) or the
// lights at infinity are that bright along it (a uniform sky never is).
bool may_see_bright_emission(const RenderScene& sc, const Ray& ray) {
  if (sc.light_selection.may_meet_finite_emitter(ray.o, ray.d)) return true;
  RGB Le(0);
  for (int li : sc.infinite_lights) Le += infinite_light_radiance(sc.lights[li], ray.d);
  return Le.luminance() > 2 * mean_sky_luminance(sc);
}

// Adds weight x the emission `ray` meets (emission_seen) to L where it is brighter than
// twice the mean sky, and says whether it did: a smooth reflection's emission counted at
// every hit, a reflected path then going on without it (trace_path, at subsurface entries
// and smooth glass). Any rule that looks at the emission alone keeps the estimate unbiased.
// Where it cannot be that bright (may_see_bright_emission) the ray is not traced: the
// same result.
bool add_bright_emission_seen(const RenderScene& sc, const Ray& ray, RGB weight, PathCounters& counters, RGB& L) {
  if (!may_see_bright_emission(sc, ray)) return false;
  const RGB Le = emission_seen(sc, ray, counters);
  if (!(Le.luminance() > 2 * mean_sky_luminance(sc))) return false;
  L += weight * Le;
  return true;
}

// One light sample from each group of the light selection (finite lights, lights at
// infinity: lights/light_selection.h), two dimensions each. With SkyRule::Outweighed (the
// subsurface exits), where the finite lights outweigh a uniform sky
// (LightSelection::uniform_sky_outweighed, from the importance sum the first choice
// computes), the sky's sample is not taken (its two dimensions are): the scattered
// direction, whose vertex says the same rule, finds it at MIS weight one. With
// SkyRule::GivesWay (the probes' exits, some walk strategies') no uniform sky is chosen.
template <class Scatter>
RGB estimate_direct(const RenderScene& sc, Vec3 p, Vec3 n, int medium, Sampler& sampler, PathCounters& counters,
                    Scatter&& scatter, SkyRule sky = SkyRule::Sampled) {
  float finite_importance = 0;
  RGB L = estimate_direct_group(sc, p, n, medium, sampler, counters, scatter, 0, &finite_importance, sky);
  if (sc.light_selection.groups(n) == 2) {
    if (sky != SkyRule::Outweighed || !sc.light_selection.uniform_sky_outweighed(finite_importance))
      L += estimate_direct_group(sc, p, n, medium, sampler, counters, scatter, 1, nullptr, sky);
    else
      sampler.get2d();
  }
  return L;
}

}  // namespace

RGB transmitted_irradiance(const RenderScene& sc, Vec3 p, Vec3 n, float eta, int medium, Sampler& sampler,
                           PathCounters& counters, const RoughExitTable* rough, int* split_budget) {
  auto transmitted_cos = [&](Vec3 wi) {
    float c = dot(wi, n);
    if (!(c > 0)) return 0.0f;
    return (rough ? rough->at(c) : 1 - fresnel_dielectric(c, eta)) * c;
  };
  Vec3 p_out = offset_ray_origin(p, n, n);
  // Direct light by next-event estimation (MIS against the cosine sampling below).
  RGB E = estimate_direct(sc, p_out, n, medium, sampler, counters, [&](Vec3 wi) {
    return std::pair{RGB(transmitted_cos(wi)), cosine_hemisphere_pdf(dot(wi, n))};
  });
  // Everything else along one cosine-distributed direction.
  Vec3 local = sample_cosine_hemisphere(sampler.get2d());
  if (local.z <= 0) return E;
  Vec3 wi = Frame(n).to_world(local);
  PathStart start;
  start.from_camera = false;
  start.prev_pdf = cosine_hemisphere_pdf(local.z);
  start.prev_p = p_out;
  start.prev_n = n;
  start.depth = 1;
  start.first_dimension = Sampler::region(sampler.dimension(), 0x1aadu);
  start.split_budget = split_budget;
  RGB Li = trace_path(sc, Ray{p_out, wi}, medium, sampler, counters, start);
  return E + Li * (transmitted_cos(wi) / start.prev_pdf);
}

RGB shadow_transmittance(const RenderScene& sc, Vec3 origin, Vec3 dir, float distance, int medium,
                         PathCounters& counters) {
  RGB tr(1);
  if (!sc.has_interfaces) {
    // No index-matched boundary: any hit blocks, and the medium cannot change.
    const Ray shadow{origin, dir, distance};
    counters.count(shadow);
    if (sc.embree->occluded(shadow)) return RGB(0);
    if (medium >= 0) tr = sc.media[medium].transmittance(distance);
    return tr;
  }
  {
    // One occlusion query: the interfaces crossed, or the first other shape, which blocks.
    constexpr int kCapacity = 32;
    EmbreeScene::RawHit raw[kCapacity];
    const Ray shadow{origin, dir, distance};
    counters.count(shadow);
    const int n = sc.embree->pass_through_hits(shadow, sc.interface_shape, raw, kCapacity);
    if (n == EmbreeScene::kBlocked) return RGB(0);
    if (n >= 0) {
      float t_medium = 0;  // where the medium the ray is in began
      float next = 0;      // a hit closer than this to the one before is the same crossing
      for (int i = 0; i < n; ++i) {
        if (raw[i].t < next) continue;
        SurfaceHit hit;
        sc.embree->fill_hit(raw[i], shadow, hit);
        next = raw[i].t + surface_offset(hit.p);
        if (medium >= 0) tr *= sc.media[medium].transmittance(hit.t - t_medium);
        if (tr.is_black()) return tr;
        medium = medium_after_crossing(sc.shapes[hit.shape], dir, hit.ng, medium);
        t_medium = hit.t;
      }
      if (medium >= 0) tr *= sc.media[medium].transmittance(distance - t_medium);
      return tr;
    }
  }
  // More interfaces than the buffer holds: query by query.
  Vec3 o = origin;
  float remaining = distance;
  for (int crossing = 0; crossing < kMaxInterfaceCrossings; ++crossing) {
    const Ray shadow{o, dir, remaining};
    counters.count(shadow);
    SurfaceHit hit;
    if (!sc.embree->intersect(shadow, hit)) {
      if (medium >= 0) tr *= sc.media[medium].transmittance(remaining);
      return tr;
    }
    const Shape& s = sc.shapes[hit.shape];
    if (!sc.materials[s.material].is_interface()) return RGB(0);
    if (medium >= 0) tr *= sc.media[medium].transmittance(hit.t);
    if (tr.is_black()) return tr;
    medium = medium_after_crossing(s, dir, hit.ng, medium);
    Vec3 next = offset_ray_origin(hit.p, hit.ng, dir);
    if (remaining != kInf) remaining -= dot(next - o, dir);
    o = next;
    if (remaining <= 0) return tr;
  }
  ++counters.truncated;
  return RGB(0);
}

RGB trace_path(const RenderScene& sc, Ray ray, int medium, Sampler& sampler, PathCounters& counters,
               const PathStart& start) {
  RGB L(0), beta(1);
  float eta_scale = 1;
  bool specular = start.from_camera || start.prev_specular;  // the last scattering was specular (or the camera): no MIS on emission
  float prev_pdf = start.prev_pdf;    // solid-angle pdf of the last scattering direction
  // The last scattering event's next-event point and normal (integrator.h PathStart).
  Vec3 prev_p = start.from_camera ? ray.o : start.prev_p;
  Vec3 prev_n = start.from_camera ? Vec3(0, 0, 0) : start.prev_n;
  SkyRule prev_sky = start.from_camera ? SkyRule::Sampled : start.prev_sky;
  int depth = start.depth, crossings = 0;
  // Every vertex so far a smooth specular one (glass, a mirror) or none: what the camera
  // sees directly, through glass or in a mirror. Its first subsurface entry is the
  // camera's first entry (below), with the exits and strategies that serve it.
  bool camera_chain = start.from_camera && start.depth == 0;
  // The emission at the next surface (or at infinity) was counted already (a subsurface
  // entry's reflection, below): the path goes on from there without it.
  bool emission_counted = false;
  uint64_t vertex_dimension = start.first_dimension;  // this vertex's block (integrator.h)
  const int max_depth = sc.settings.max_depth;
  int own_split_budget = kSplitBudgetPerSample;
  int& split_budget = start.split_budget ? *start.split_budget : own_split_budget;
  // Russian roulette after the second bounce on max(throughput) x eta scale (pbrt-v4
  // sec. 14.1.3), below `threshold` (russian_roulette.h); reweights beta when the path survives.
  auto survives_roulette = [&](float threshold) {
    if (depth <= 1) return true;
    const float p = roulette_survival(beta.max() * eta_scale, threshold);
    if (p >= 1) return true;
    if (!(sampler.get1d() < p)) return false;
    beta /= p;
    return true;
  };

  // The camera's first smooth reflection, split off with weight `weight` (F, or F times the
  // glass lobe's weight) as the path `reflected`: followed always where it may see a bright
  // emitter (a small light's highlight, which it was split off for). Elsewhere Russian
  // roulette (pbrt-v4's rule, russian_roulette.h) on the branch's throughput max(beta) x
  // eta scale x weight: where a sky shines, at the reflected path's first vertex
  // (PathStart::first_vertex_roulette), so that the sky its first ray meets counts in full
  // for the price of that ray; with no sky, before the ray is traced, since nothing it
  // meets directly can then be bright. Rouletted before the ray, a dark object's
  // reflection of a uniform sky, most of what it shows, was met by one sample in 1/F:
  // on bench/vs_cycles' f08 (the bust, sky only, dark) the variance fell to 0.42x (walk)
  // and 0.53x (disk) when the sky is met by every sample (docs/rendering.md).
  // Returns the probability the reflected path is traced with, 0 when it is not; the
  // decision's number comes from a region of its own.
  auto reflection_survival = [&](const Ray& reflected_ray, float weight, PathStart& reflected) -> float {
    if (!start.reflection_roulette || may_see_bright_emission(sc, reflected_ray)) return 1.0f;
    const float rr = beta.max() * eta_scale * weight;
    if (mean_sky_luminance(sc) > 0) {
      reflected.first_vertex_roulette = rr;
      return 1.0f;
    }
    const float q = roulette_survival(rr, kSurfaceRouletteThreshold);
    if (q >= 1) return 1.0f;
    sampler.set_dimension(Sampler::region(sampler.dimension(), 0x5e1eu));
    return sampler.get1d() < q ? q : 0.0f;
  };
  // PathStart::first_vertex_roulette, at the path's first vertex (once).
  bool first_vertex = true;
  auto first_vertex_survives = [&]() {
    if (!first_vertex) return true;
    first_vertex = false;
    if (!(start.first_vertex_roulette > 0)) return true;
    const float q = roulette_survival(start.first_vertex_roulette, kSurfaceRouletteThreshold);
    if (q >= 1) return true;
    const Sampler::Position resume = sampler.position();
    sampler.set_dimension(Sampler::region(start.first_dimension, 0x5e1eu));
    const bool survives = sampler.get1d() < q;
    sampler.restore(resume);
    if (survives) beta /= q;
    return survives;
  };

  // A textured `volumetric` object: the path takes the medium of the point where it
  // entered and keeps it while inside (volumetric_texture.h); elsewhere sc.media.
  HomogeneousMedium entered;
  int entered_medium = -1;
  auto medium_of = [&](int m) -> const HomogeneousMedium& { return m == entered_medium ? entered : sc.media[m]; };

  const uint64_t last_stratified = start.first_dimension + kStratifiedVertices * kVertexDimensions;
  for (;; vertex_dimension += kVertexDimensions) {
    if (vertex_dimension < last_stratified)
      sampler.set_dimension(vertex_dimension);
    else
      sampler.set_dimension(vertex_dimension, 0);  // deep vertices: the sample's PCG32 stream
    SurfaceHit hit;
    counters.count(ray);
    bool found = sc.embree->intersect(ray, hit);
    float t_hit = found ? hit.t : kInf;

    if (medium >= 0) {
      const HomogeneousMedium& m = medium_of(medium);
      const MediumSegment segment = medium_segment(m, t_hit);
      // The free flight's channel and distance, jointly stratified.
      const Vec2 u_flight = sampler.get2d();
      // Direct light in-scattered anywhere on the segment, at a point drawn for it alone
      // (decoupled from the free flight below, as Cycles' volume integrator does): the path
      // gathers it also where it passes through, and its scattering events do no next-event
      // estimation of their own. A path that finds a light by phase sampling weighs itself
      // against this estimate at its own scattering point: the two weights sum to one at every
      // point, so any distance distribution of either strategy keeps the sum unbiased.
      // The point takes the free flight's distance number u (its channel has a number of
      // its own). In the flight's channel, where the flight scatters at t_s the point, the
      // truncated exponential's quantile at u (1 - T(t_max)), lies on [0, t_s], the stretch
      // the path travels; where it passes through, toward the segment's end. Both are drawn
      // on every segment whatever the other's outcome, so the light sample keeps its exact
      // distribution on its segment and the path its own: the sum stays unbiased (the
      // expectation of a sum is the sum of the expectations, however the terms correlate).
      // On bench/vs_cycles' index-matched medium and variants (4x denser, lower albedo,
      // g 0.8, the light behind) the variance fell to 0.86-0.93x of an independent number
      // for the point (docs/rendering.md, "Direct light in a medium").
      const float u_segment_channel = sampler.get1d();
      if (sc.medium_sees_lights[medium] && depth < max_depth) {
        const SegmentPoint sp = sample_segment_point(m, segment, beta, u_segment_channel, u_flight.y);
        if (sp.valid) {
          const Vec3 wo = -ray.d;
          const float g = m.g;
          L += beta * sp.weight *
               estimate_direct(sc, ray.o + ray.d * sp.t, Vec3(0, 0, 0), medium, sampler, counters, [&](Vec3 wi) {
                 float ph = henyey_greenstein(dot(-wo, wi), g);
                 return std::pair{RGB(ph), ph};
               });
        } else {
          sampler.get2d();  // the light sample's two dimensions, so that those after it do not shift
        }
      } else if (sc.medium_sees_lights[medium]) {
        sampler.get2d();
      }
      const FreeFlight flight = sample_free_flight(m, segment, beta, u_flight.x, u_flight.y);
      if (!flight.valid) break;
      beta *= flight.weight;
      if (!beta.is_finite() || beta.is_black()) break;
      if (flight.scattered) {
        if (!first_vertex_survives()) break;
        // Scattering event in the medium.
        Vec3 p = ray.o + ray.d * flight.t;
        if (depth++ >= max_depth) break;
        const float g = m.g;
        // Sample the phase function about the propagation direction (weight 1).
        const Vec2 u_phase = sampler.get2d();
        float cos_theta = sample_henyey_greenstein_cos(u_phase.x, g);
        Vec3 wi = direction_about(ray.d, cos_theta, u_phase.y);
        prev_pdf = henyey_greenstein(cos_theta, g);
        specular = false;
        camera_chain = false;
        prev_p = p;
        prev_n = Vec3(0, 0, 0);
        prev_sky = SkyRule::Sampled;
        ray = Ray{p, wi};
        if (!survives_roulette(sc.medium_sees_lights[medium] ? kMediumRouletteThreshold : kSurfaceRouletteThreshold))
          break;
        continue;
      }
      // Passed through to the surface (or to infinity).
    }

    if (!found) {
      if (emission_counted) break;
      for (int li : sc.infinite_lights) {
        const Light& light = sc.lights[li];
        RGB Le = infinite_light_radiance(light, ray.d);
        if (Le.is_black()) continue;
        float w = specular ? 1.0f
                           : power_heuristic(prev_pdf, sc.light_selection.pmf(li, prev_p, prev_n, prev_sky) *
                                                           light_pdf(light, prev_p, ray.d, {}, {}, prev_n));
        L += beta * Le * w;
      }
      break;
    }

    const Shape& s = sc.shapes[hit.shape];
    if (s.first_light >= 0 && !emission_counted) {
      int li = s.first_light + (s.type == Shape::Type::Mesh ? hit.prim : 0);
      const Light& light = sc.lights[li];
      RGB Le = area_light_radiance(light, hit.ng, -ray.d);
      if (!Le.is_black()) {
        float w = specular ? 1.0f
                           : power_heuristic(prev_pdf, sc.light_selection.pmf(li, prev_p, prev_n, prev_sky) *
                                                           light_pdf(light, prev_p, ray.d, hit.p, hit.ng));
        L += beta * Le * w;
      }
    }

    emission_counted = false;
    if (!first_vertex_survives()) break;
    // A mix material resolves to one of its materials here, once per hit (material.h).
    const Material& mat = sc.materials[resolve_material(sc.materials, sc.textures, s.material, hit, -ray.d,
                                                        sampler.sample_hash(vertex_dimension))];
    if (mat.is_interface()) {
      // An index-matched boundary: change medium, keep going in the same direction.
      if (++crossings > kMaxInterfaceCrossings * 16) {
        ++counters.truncated;
        break;
      }
      medium = medium_after_crossing(s, ray.d, hit.ng, medium);
      ray.o = offset_ray_origin(hit.p, hit.ng, ray.d);
      ray.tmax = kInf;
      continue;
    }
    if (depth++ >= max_depth) break;
    Vec3 wo = -ray.d;
    hit.ns = shading_normal_seen_from(hit, wo);  // geometry/shading_normal.h

    if (mat.type == Material::Type::Subsurface) {
      // The boundary is a smooth dielectric: reflection is sampled by Fresnel,
      // transmitted light leaves the object where the material's method says
      // (render/subsurface/subsurface_method.h).
      const SubsurfaceMaterial& sm = *sc.subsurface[mat.subsurface];
      float cos_o = dot(wo, hit.ng);
      if (cos_o <= 0) {
        // Reached from inside (thin or open geometry): let the path pass.
        ray.o = offset_ray_origin(hit.p, hit.ng, ray.d);
        ray.tmax = kInf;
        continue;
      }
      const bool first_entry = camera_chain;
      camera_chain = false;
      std::optional<Vec3> refracted;
      const BSDF boundary = sm.entry_boundary(hit);
      float F = fresnel_dielectric(dot(wo, hit.ns), sm.entry_eta);
      if (boundary.is_rough()) {
        // A rough boundary: the rough dielectric sampled. Reflection continues the path,
        // its emission MIS-weighted against light sampling of the reflection lobe here
        // (the transmitted side is the method's: no lights there); transmission enters
        // the method along the sampled direction, the 1/eta^2 radiance factor omitted as
        // for the smooth entry (the exit's cancels it).
        const bool entry_nee = start.rough_glass_nee;
        const Vec3 p_out = offset_ray_origin(hit.p, hit.ng, hit.ng);
        if (entry_nee) {
          L += beta * estimate_direct(sc, p_out, hit.ng, medium, sampler, counters, [&](Vec3 wi) {
                 if (dot(wi, hit.ng) <= 0 || !shading_side_agrees(hit, wi)) return std::pair{RGB(0), 0.0f};
                 return std::pair{bsdf_eval(boundary, wo, wi), bsdf_pdf(boundary, wo, wi)};
               });
        }
        const float u_lobe = sampler.get1d();
        const auto bs = bsdf_sample(boundary, wo, u_lobe, sampler.get2d());
        if (!bs || !shading_side_agrees(hit, bs->wi)) break;
        if (!bs->transmission) {
          beta *= bs->weight;
          specular = !entry_nee;  // without light sampling here: emission counts in full
          prev_pdf = bs->pdf;
          prev_p = entry_nee ? p_out : hit.p;
          prev_n = hit.ng;
          prev_sky = SkyRule::Sampled;
          ray = Ray{offset_ray_origin(hit.p, hit.ng, bs->wi), bs->wi};
          if (!beta.is_finite() || beta.is_black()) break;
          continue;
        }
        beta *= bs->weight * bs->eta_scale;
        refracted = bs->wi;
      } else if (start.split_first_hit && start.from_camera && start.depth == 0 && depth == 1) {
        // The camera's first hit is split: reflection and transmission are both followed,
        // weighted F and 1 - F (unbiased: one sample of each term of F L_r + (1 - F) L_t).
        // Chosen by Fresnel, a sharp highlight of a small light rests on the few per cent
        // of samples that reflect: on the skin-like sphere it made half the image's error.
        // Where the reflection cannot see a bright emitter it is rouletted on its weight F
        // (reflection_survival): what lies beyond a sky's is a few per cent of dim light.
        const Vec3 wi = reflect(wo, hit.ns);
        const Ray reflected_ray{offset_ray_origin(hit.p, hit.ng, wi), wi};
        const uint64_t resume = sampler.dimension();
        const bool reflects = F > 0 && shading_side_agrees(hit, wi);  // else into the surface: no light
        PathStart reflected;  // after a specular bounce: emission counts in full
        reflected.depth = depth;
        reflected.rough_glass_nee = start.rough_glass_nee;
        reflected.reflection_emission = start.reflection_emission;
        reflected.reflection_roulette = start.reflection_roulette;
        reflected.first_dimension = Sampler::region(resume, 0x5e1fu);
        reflected.split_budget = &split_budget;
        reflected.subsurface_strategies = start.subsurface_strategies;
        if (const float q = reflects ? reflection_survival(reflected_ray, F, reflected) : 0.0f; q > 0) {
          const RGB Lr = beta * (F / q) * trace_path(sc, reflected_ray, medium, sampler, counters, reflected);
          L += Lr;
          if (start.subsurface_record) start.subsurface_record->camera_reflection += Lr;
        }
        sampler.set_dimension(resume);
        beta *= 1 - F;
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
        const Vec3 wi = reflect(wo, hit.ns);
        const Ray reflected{offset_ray_origin(hit.p, hit.ng, wi), wi};
        const bool reflects = shading_side_agrees(hit, wi);  // else into the surface: no light
        const bool counted = start.reflection_emission && medium < 0 && F > 0 && reflects &&
                             add_bright_emission_seen(sc, reflected, beta * F, counters, L);
        if (reflect_path) {
          if (!reflects) break;
          specular = true;
          prev_pdf = F;
          prev_p = hit.p;
          emission_counted = counted;
          ray = reflected;
          continue;
        }
      }
      // The exit sampler draws from its own region; the exit's light and lobe from this block.
      const uint64_t after_exit = sampler.dimension();
      sampler.set_dimension(Sampler::region(after_exit, 0x55e1u), kStratifiedExitDimensions);
      const ObjectTracer tracer(*sc.embree, sc.object_of_shape, hit, counters);
      auto irradiance = [&](Vec3 p, Vec3 n, float eta, Sampler& smp) {
        return transmitted_irradiance(sc, p, n, eta, medium, smp, counters, sm.exit_table ? &*sm.exit_table : nullptr,
                                      &split_budget);
      };
      auto interior_albedo = [&](const SurfaceHit& h) {
        const Material& m = sc.materials[sc.shapes[h.shape].material];
        return m.type == Material::Type::Diffuse ? bsdf_at(m, sc.textures, h).albedo : RGB(0);
      };
      const int strategy = start.subsurface_strategies ? (*start.subsurface_strategies)[std::size_t(mat.subsurface)] : 0;
      // Whether uniform skies are light-sampled at this material's exits (its method's rule,
      // a walk's by its strategy: SubsurfaceMaterial::exit_sky_rule).
      const SkyRule exit_sky = sm.exit_sky_rule(strategy);
      // Under uniform skies alone that give way at the exits, no light is sampled there:
      // the exits' light samples are skipped (they would choose none).
      const bool exit_light_none = exit_sky == SkyRule::GivesWay && sc.light_selection.gives_way_leaves_none();
      // Light sampled through a rough boundary from inside (a walk's exits), on the
      // outside, in the medium the path entered from.
      auto light_through = [&](Vec3 p, Vec3 n, const BSDF& b, Vec3 wo_in, Sampler& smp) {
        if (!start.rough_glass_nee) return RGB(0);
        return estimate_direct(sc, offset_ray_origin(p, n, n), n, medium, smp, counters, [&](Vec3 wi) {
          if (!shading_side_agrees(n, b.n, wi) || dot(wi, n) <= 0) return std::pair{RGB(0), 0.0f};
          return std::pair{bsdf_eval(b, wo_in, wi), bsdf_pdf(b, wo_in, wi)};
        });
      };
      // Direct light leaving through the exit lobe sw at a point, from the outside's medium.
      auto light_through_lobe = [&](const SurfaceHit& at, const BSDF& sw, Sampler& smp) {
        if (exit_light_none) return RGB(0);
        return estimate_direct(
            sc, offset_ray_origin(at.p, at.ng, at.ng), at.ng, medium, smp, counters,
            [&](Vec3 wi) {
              if (!shading_side_agrees(at, wi)) return std::pair{RGB(0), 0.0f};
              return std::pair{bsdf_eval(sw, at.ns, wi), bsdf_pdf(sw, at.ns, wi)};
            },
            exit_sky);
      };
      auto exit_light = [&](const SurfaceHit& at, Sampler& smp) {
        RoughExitTable table_at;  // a textured roughness: the table of the point's alpha
        return light_through_lobe(at, sm.exit_lobe(at, table_at), smp);
      };
      // A nested path from an exit, as this path would go on from there: its settings, the
      // vertex after it (prev_*) the caller's.
      auto nested_way_on = [&](uint64_t first_dimension) {
        PathStart way_on;
        way_on.from_camera = false;
        way_on.depth = depth;
        way_on.first_dimension = first_dimension;
        way_on.rough_glass_nee = start.rough_glass_nee;
        way_on.reflection_emission = start.reflection_emission;
        way_on.split_budget = &split_budget;
        way_on.subsurface_strategies = start.subsurface_strategies;
        return way_on;
      };
      // A nested way on from the exit point `at` through its lobe (a path splitting's copy,
      // or another exit's way on): the lobe sampled from the sampler's current dimension,
      // the path from first_dimension; adds beta x weight / divisor x its radiance to L.
      auto go_on_from_exit = [&](const SurfaceHit& at, const BSDF& lobe, const RGB& weight, float divisor,
                                 uint64_t first_dimension) {
        const float u_lobe = sampler.get1d();
        const auto b = bsdf_sample(lobe, at.ns, u_lobe, sampler.get2d());
        if (!b || !shading_side_agrees(at, b->wi)) return;
        const RGB beta_k = beta * weight * b->weight / divisor;
        if (!beta_k.is_finite() || beta_k.is_black()) return;
        const Vec3 p_out_k = offset_ray_origin(at.p, at.ng, at.ng);
        PathStart way_on = nested_way_on(first_dimension);
        way_on.prev_pdf = b->pdf;
        way_on.prev_p = p_out_k;
        way_on.prev_n = at.ng;
        way_on.prev_sky = exit_sky;
        L += beta_k * trace_path(sc, Ray{p_out_k, b->wi}, medium, sampler, counters, way_on);
      };
      // A nested way on along an Along exit's direction e.direction (another exit's, at the
      // camera's first entry), as the path itself goes on below; adds beta x e.weight /
      // divisor x its radiance to L.
      auto go_on_along = [&](const SubsurfaceExit& e, float divisor, uint64_t first_dimension) {
        const RGB beta_k = beta * e.weight / divisor;
        if (!beta_k.is_finite() || beta_k.is_black()) return;
        const bool weighed = e.direction_pdf > 0 && start.rough_glass_nee;
        PathStart way_on = nested_way_on(first_dimension);
        way_on.prev_specular = !weighed;
        way_on.prev_pdf = e.direction_pdf;
        way_on.prev_p = weighed ? offset_ray_origin(e.hit.p, e.hit.ng, e.hit.ng) : e.hit.p;
        way_on.prev_n = e.hit.ng;
        way_on.prev_sky = SkyRule::Sampled;  // light_through's samples
        L += beta_k * trace_path(sc, Ray{offset_ray_origin(e.hit.p, e.hit.ng, e.direction), e.direction}, medium,
                                 sampler, counters, way_on);
      };
      // The camera's first entry averages several exits (below): the scene's
      // subsurfacesamples through the exit lobe, or more (a walk with one colour channel
      // per exit, whatever its boundary).
      const int first_entry_exits = first_entry ? sm.first_entry_exits(strategy, sc.settings.subsurface_samples) : 0;
      SubsurfaceEntry entry{hit,        wo,        tracer,   irradiance, interior_albedo, light_through,
                            exit_light, refracted, strategy, first_entry_exits > 0 ? 0 : -1, exit_light_none};
      if (first_entry && start.subsurface_record && start.subsurface_record->material < 0)
        start.subsurface_record->material = mat.subsurface;
      // The probes' exits at the camera's first entry are one stratified sequence of the
      // pixel's samples: exit k of sample i draws Sobol' index K i + k of dimensions of their
      // own (one set per exit count K: Sampler::set_split). Against K independent regions,
      // variance 0.84-0.89x with the disk's two exits (docs/probe-sampling.md, "The exits as
      // one sequence"); a walk's keep their regions (SubsurfaceMaterial::exits_as_one_sequence).
      const bool split_exits = first_entry_exits > 1 && sm.exits_as_one_sequence();
      const uint64_t exits_region =
          split_exits ? Sampler::region(after_exit, kSplitExitsTag + uint32_t(first_entry_exits)) : 0;
      if (split_exits) {
        sampler.set_dimension(exits_region, kStratifiedExitDimensions);
        sampler.set_split(0, uint32_t(first_entry_exits));
      }
      SubsurfaceExit ex;
      const bool exited = sample_subsurface_exit(sm, entry, sampler, ex);
      sampler.set_split(0, 1);
      // Several exits, each from a sampler region of its own, their direct light averaged
      // (each exit's estimate is unbiased, so is their mean); the path goes on from the
      // first (at the camera's first entry from each, below). At the camera's first entry
      // first_entry_exits of them (subsurfacesamples, or more: above): the entry's cost
      // (the camera ray, the reflection split off, the path after the exit) is paid once;
      // on the skin-like sphere two exits halve the variance for 1.2-1.4x the render time.
      // At a later entry, as many as path splitting gives the path's throughput
      // (path_splitting.h): a heavy path's exit light split, not its way on.
      const int exits = first_entry                ? first_entry_exits
                        : !sm.exits_through_lobe() ? 1
                                                   : split_count(beta, sc.settings.split_threshold, split_budget);
      if (exits > 1) {
        RoughExitTable table_at;  // a textured roughness: the table of the point's alpha
        auto exit_estimate = [&](const SubsurfaceExit& e, bool found) {
          RGB est = e.gathered;
          if (found && e.kind == SubsurfaceExit::Kind::ThroughLobe && !e.exit_light_gathered)
            est += e.weight * light_through_lobe(e.hit, sm.exit_lobe(e.hit, table_at), sampler);
          return est;
        };
        // At the camera's first entry every exit also goes on (continue_all): each of the
        // n ways on carries 1/n of its exit's weight, the first as the path itself, the
        // others as nested paths from their exits (the mean of n unbiased estimates). With
        // the first alone going on with its whole weight, the light its lobe finds by MIS
        // (about half of a uniform sky's) rested on one walk of the n. On the family of
        // bench/vs_cycles: variance 0.80x on the milk sphere under the sky alone (f02),
        // 0.70-0.85x on the bust, for 4-9 % more time (docs/rendering.md).
        const bool continue_all = first_entry;
        RGB sum = exit_estimate(ex, exited);
        for (int k = 1; k < exits; ++k) {
          SubsurfaceExit other;
          if (entry.exit_index >= 0) entry.exit_index = k;
          if (split_exits) {
            sampler.set_dimension(exits_region, kStratifiedExitDimensions);
            sampler.set_split(uint32_t(k), uint32_t(exits));
          } else {
            sampler.set_dimension(Sampler::region(after_exit, 0x5a3e0u + uint32_t(k)), kStratifiedExitDimensions);
          }
          const bool found = sample_subsurface_exit(sm, entry, sampler, other);
          sampler.set_split(0, 1);
          sum += exit_estimate(other, found);
          if (!continue_all || !found) continue;
          if (other.kind == SubsurfaceExit::Kind::Along) {
            go_on_along(other, float(exits), Sampler::region(after_exit, 0x5c0f0u + uint32_t(k)));
            continue;
          }
          if (other.kind != SubsurfaceExit::Kind::ThroughLobe) continue;
          sampler.set_dimension(Sampler::region(after_exit, 0x5c0e0u + uint32_t(k)), kStratifiedExitDimensions);
          go_on_from_exit(other.hit, sm.exit_lobe(other.hit, table_at), other.weight, float(exits),
                          Sampler::region(after_exit, 0x5c0f0u + uint32_t(k)));
        }
        ex.gathered = sum / float(exits);
        ex.exit_light_gathered = true;
        if (continue_all) ex.weight /= float(exits);
      }
      sampler.set_dimension(after_exit);
      L += beta * ex.gathered;
      if (!exited) {
        if (ex.truncated) ++counters.truncated;
        break;
      }
      if (ex.kind == SubsurfaceExit::Kind::Emitted) {
        L += beta * ex.radiance;
        break;
      }
      beta *= ex.weight;
      if (!beta.is_finite() || beta.is_black()) break;
      if (ex.kind == SubsurfaceExit::Kind::Along) {
        // Through a rough boundary whose lights were sampled: light found along the
        // direction is weighed against those samples, taken from the same point and normal.
        const bool weighed = ex.direction_pdf > 0 && start.rough_glass_nee;
        specular = !weighed;
        prev_pdf = ex.direction_pdf;
        prev_p = weighed ? offset_ray_origin(ex.hit.p, ex.hit.ng, ex.hit.ng) : ex.hit.p;
        prev_n = ex.hit.ng;
        prev_sky = SkyRule::Sampled;  // light_through's samples
        ray = Ray{offset_ray_origin(ex.hit.p, ex.hit.ng, ex.direction), ex.direction};
        continue;
      }
      // Leave through the exit lobe Sw at the exit point (normalised Fresnel, or the
      // rough boundary's transmittance): its direct light, unless the method gathered it
      // (SubsurfaceExit::exit_light_gathered), and the lobe sampled for the way on.
      RoughExitTable exit_table_here;  // a textured roughness: the table of the exit point's alpha
      const BSDF sw = sm.exit_lobe(ex.hit, exit_table_here);
      if (!ex.exit_light_gathered) L += beta * light_through_lobe(ex.hit, sw, sampler);
      Vec3 p_out = offset_ray_origin(ex.hit.p, ex.hit.ng, ex.hit.ng);
      // A heavy path goes on as several copies from the exit (path_splitting.h): this one
      // and n - 1 nested paths, each with its own direction through the lobe, from a
      // sampler region of its own.
      if (const int copies = split_count(beta, sc.settings.split_threshold, split_budget); copies > 1) {
        beta /= float(copies);
        const Sampler::Position resume = sampler.position();
        const uint64_t here = resume.dimension;
        for (int k = 1; k < copies; ++k) {
          sampler.set_dimension(Sampler::region(here, 0x5b117u + uint32_t(k)), kStratifiedExitDimensions);
          go_on_from_exit(ex.hit, sw, RGB(1), 1.0f, Sampler::region(here, 0x5b127u + uint32_t(k)));
        }
        sampler.restore(resume);
      }
      const float u_exit_lobe = sampler.get1d();
      auto bs = bsdf_sample(sw, ex.hit.ns, u_exit_lobe, sampler.get2d());
      if (!bs || !shading_side_agrees(ex.hit, bs->wi)) break;
      beta *= bs->weight;
      specular = false;
      prev_pdf = bs->pdf;
      prev_p = p_out;
      prev_n = ex.hit.ng;
      prev_sky = exit_sky;
      ray = Ray{p_out, bs->wi};
      if (!beta.is_finite() || beta.is_black()) break;
      if (!survives_roulette(kSurfaceRouletteThreshold)) break;
      continue;
    }

    BSDF bsdf = bsdf_at(mat, sc.textures, hit);
    // The random streams of a layered BSDF's estimates: fresh for every vertex (bsdf.h).
    if (bsdf.type == BSDF::Type::Coated) bsdf.seed = sampler.sample_hash(vertex_dimension ^ 0xc0a7edull);
    // Shadow rays leave on the side of the light; the medium there is the one the path
    // is in, since Lambertian reflection stays on the side of wo.
    const Vec3 p_out = offset_ray_origin(hit.p, hit.ng, wo);
    const Vec3 surface_n = dot(hit.ng, wo) >= 0 ? hit.ng : -hit.ng;
    // Lights are sampled wherever the BSDF has a density (not at smooth glass or mirrors).
    // PathStart::rough_glass_nee off: none at rough glass, whose emission is then found by
    // the sampled direction alone (the estimator before light sampling there; tests).
    const bool rough_glass = bsdf.type == BSDF::Type::Dielectric && bsdf.is_rough();
    const bool nee = !bsdf.is_specular() && (!rough_glass || start.rough_glass_nee);
    // Diffuse transmission and rough glass sample the lights on both sides, each from a
    // point and normal on its own side (the medium behind for transmission), each counting
    // only the directions of its side: a direction sampled into either side then meets
    // its emission MIS-weighted against the light sampling of that side (prev_p, prev_n
    // below).
    const bool two_sided_nee = nee && (bsdf.type == BSDF::Type::DiffuseTransmission || rough_glass);
    const Vec3 p_back = two_sided_nee ? offset_ray_origin(hit.p, hit.ng, -wo) : p_out;
    if (nee) {
      L += beta * estimate_direct(sc, p_out, surface_n, medium, sampler, counters, [&](Vec3 wi) {
             if (two_sided_nee && dot(wi, surface_n) <= 0) return std::pair{RGB(0), 0.0f};
             if (!shading_side_agrees(hit, wi)) return std::pair{RGB(0), 0.0f};
             return std::pair{bsdf_eval(bsdf, wo, wi), bsdf_pdf(bsdf, wo, wi)};
           });
    }
    if (two_sided_nee) {
      const int medium_behind = medium_after_crossing(s, -wo, hit.ng, medium);
      L += beta * estimate_direct(sc, p_back, -surface_n, medium_behind, sampler, counters, [&](Vec3 wi) {
             if (dot(wi, surface_n) >= 0 || !shading_side_agrees(hit, wi)) return std::pair{RGB(0), 0.0f};
             return std::pair{bsdf_eval(bsdf, wo, wi), bsdf_pdf(bsdf, wo, wi)};
           });
    }
    float u_lobe = sampler.get1d();
    Vec2 u_dir = sampler.get2d();
    bool split = false;  // the camera's first hit on smooth glass: both sides followed
    if (bsdf.type == BSDF::Type::Dielectric && bsdf.is_specular() && start.split_first_hit && start.from_camera &&
        start.depth == 0 && depth == 1) {
      // The camera's first hit on glass is split like a subsurface entry: the reflection
      // is followed with weight F, the transmission below with 1 - F (one sample of each
      // term; the sampled lobes' weights are F/F and (1 - F)/(1 - F) times 1/eta^2).
      // The reflection as at a subsurface entry (reflection_survival).
      const float F = fresnel_dielectric(dot(wo, bsdf.n), bsdf.eta);
      if (F > 0 && F < 1) {
        auto reflected = bsdf_sample(bsdf, wo, 0.0f, u_dir);
        if (reflected && !reflected->transmission) {
          const bool reflects = shading_side_agrees(hit, reflected->wi);  // else into the surface: no light
          const uint64_t resume = sampler.dimension();
          const Ray reflected_ray{offset_ray_origin(hit.p, hit.ng, reflected->wi), reflected->wi};
          PathStart rs;
          rs.depth = depth;
          rs.rough_glass_nee = start.rough_glass_nee;
          rs.reflection_emission = start.reflection_emission;
          rs.reflection_roulette = start.reflection_roulette;
          rs.first_dimension = Sampler::region(resume, 0x5e1fu);
          rs.subsurface_strategies = start.subsurface_strategies;
          if (const float q = reflects ? reflection_survival(reflected_ray, F * reflected->weight.max(), rs) : 0.0f;
              q > 0) {
            const RGB Lr = beta * reflected->weight * (F / q) * trace_path(sc, reflected_ray, medium, sampler, counters, rs);
            L += Lr;
            if (start.subsurface_record) start.subsurface_record->camera_reflection += Lr;
          }
          sampler.set_dimension(resume);
          beta *= 1 - F;
          u_lobe = 1.0f;  // the transmission below (u_lobe >= F)
          split = true;
        }
      }
    }
    // Smooth glass elsewhere, in vacuum: the reflection's emission counted at every hit, as
    // at a subsurface entry (above), the reflection then chosen with probability F as before.
    bool reflection_counted = false;
    if (bsdf.type == BSDF::Type::Dielectric && bsdf.is_specular() && !split && start.reflection_emission &&
        medium < 0) {
      const float F = fresnel_dielectric(dot(wo, bsdf.n), bsdf.eta);
      const auto reflected = F > 0 ? bsdf_sample(bsdf, wo, 0.0f, u_dir) : std::nullopt;
      if (reflected && !reflected->transmission && shading_side_agrees(hit, reflected->wi))
        reflection_counted =
            add_bright_emission_seen(sc, Ray{offset_ray_origin(hit.p, hit.ng, reflected->wi), reflected->wi},
                                     beta * reflected->weight * F, counters, L);
    }
    auto bs = bsdf_sample(bsdf, wo, u_lobe, u_dir);
    if (!bs || !shading_side_agrees(hit, bs->wi)) break;
    emission_counted = reflection_counted && !bs->transmission;
    beta *= bs->weight;
    eta_scale *= bs->eta_scale;
    specular = bs->specular || !nee;  // no light sampling here: emission counts in full
    if (!bs->specular) camera_chain = false;
    prev_pdf = bs->pdf;
    const bool behind = two_sided_nee && bs->transmission;
    prev_p = behind ? p_back : p_out;
    prev_n = behind ? -surface_n : surface_n;
    prev_sky = SkyRule::Sampled;
    if (bs->transmission) {
      const int before = medium;
      medium = medium_after_crossing(s, bs->wi, hit.ng, medium);
      if (const int v = textured_volumetric(sc, medium); v >= 0 && medium != before) {
        entered = volumetric_medium_at(sc, v, hit);
        entered_medium = medium;
      }
    }
    ray = Ray{offset_ray_origin(hit.p, hit.ng, bs->wi), bs->wi};
    if (!beta.is_finite() || beta.is_black()) break;
    if (!survives_roulette(kSurfaceRouletteThreshold)) break;
  }
  return L;
}

}  // namespace dermis
