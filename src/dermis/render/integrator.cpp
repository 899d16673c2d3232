#include "dermis/render/integrator.h"

#include <cmath>

#include "dermis/core/warp.h"
#include "dermis/geometry/shading_normal.h"
#include "dermis/materials/fresnel.h"
#include "dermis/materials/null_scattering.h"
#include "dermis/render/path/direct_light.h"
#include "dermis/render/path/emission.h"
#include "dermis/render/path/path_state.h"
#include "dermis/render/path/sampler_regions.h"
#include "dermis/render/path/subsurface_vertex.h"
#include "dermis/render/path/surface_vertex.h"
#include "dermis/render/path/volume_vertex.h"
#include "dermis/render/path_splitting.h"
#include "dermis/render/spectral_media.h"

namespace dermis {

RGB transmitted_irradiance(const RenderScene& sc, Vec3 p, Vec3 n, float eta, int medium, Sampler& sampler,
                           PathCounters& counters, const RoughExitTable* rough, int* split_budget) {
  auto transmitted_cos = [&](Vec3 wi) {
    float c = dot(wi, n);
    if (!(c > 0)) return 0.0f;
    return (rough ? rough->at(c) : 1 - fresnel_dielectric(c, eta)) * c;
  };
  Vec3 p_out = offset_ray_origin(p, n, n);
  // Direct light by next-event estimation (MIS against the cosine sampling below). In RGB:
  // the point clouds' irradiance (subsurface materials have no spectral form yet).
  RGB E = estimate_direct(sc, p_out, n, medium, sampler, counters, nullptr, [&](Vec3 wi) {
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
  start.first_dimension = Sampler::region(sampler.dimension(), kTransmittedIrradianceRegion);
  start.split_budget = split_budget;
  RGB Li = trace_path(sc, Ray{p_out, wi}, medium, sampler, counters, start);
  return E + Li * (transmitted_cos(wi) / start.prev_pdf);
}

RGB shadow_transmittance(const RenderScene& sc, Vec3 origin, Vec3 dir, float distance, int medium,
                         PathCounters& counters, const SampledWavelengths* wavelengths) {
  // A medium's transmittance over [t0, t1) of the ray from o along dir, at the path's
  // wavelengths when it has them; a grid medium's by ratio tracking.
  auto medium_tr = [&](int m, Vec3 o, float t0, float t1) {
    if (sc.grid_medium_of(m) >= 0) {
      const Ray segment{o + dir * t0, dir};
      Rng rng = tracking_rng(t1 - t0, segment);
      bool stalled = false;
      const RGB tr =
          ratio_tracking_transmittance(grid_medium_view(sc, m, wavelengths), segment, t1 - t0, rng, &stalled);
      if (stalled) ++counters.truncated;
      return tr;
    }
    return wavelengths ? scene_medium_at_wavelengths(sc, m, *wavelengths).transmittance(t1 - t0)
                       : sc.media[m].transmittance(t1 - t0);
  };
  RGB tr(1);
  if (!sc.has_interfaces) {
    // No index-matched boundary: any hit blocks, and the medium cannot change.
    const Ray shadow{origin, dir, distance};
    counters.count(shadow);
    if (sc.embree->occluded(shadow)) return RGB(0);
    if (medium >= 0) tr = medium_tr(medium, origin, 0, distance);
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
        if (medium >= 0) tr *= medium_tr(medium, origin, t_medium, hit.t);
        if (tr.is_black()) return tr;
        medium = medium_after_crossing(sc.shapes[hit.shape], dir, hit.ng, medium);
        t_medium = hit.t;
      }
      if (medium >= 0) tr *= medium_tr(medium, origin, t_medium, distance);
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
      if (medium >= 0) tr *= medium_tr(medium, o, 0, remaining);
      return tr;
    }
    const Shape& s = sc.shapes[hit.shape];
    if (!sc.materials[s.material].is_interface()) return RGB(0);
    if (medium >= 0) tr *= medium_tr(medium, o, 0, hit.t);
    if (tr.is_black()) return tr;
    medium = medium_after_crossing(s, dir, hit.ng, medium);
    Vec3 next = offset_ray_origin(hit.p, hit.ng, dir);
    if (remaining != kInfiniteDistance) remaining -= dot(next - o, dir);
    o = next;
    if (remaining <= 0) return tr;
  }
  ++counters.truncated;
  return RGB(0);
}

// The loop over a path's vertices (pbrt-v4's VolPathIntegrator::Li; Cycles' integrator
// kernels): trace the ray; through a medium (shade_volume), which may scatter the path
// before the surface; the emission met (emission.h); at the surface, an index-matched
// boundary crossed, or the vertex of its material: a subsurface boundary
// (SubsurfaceVertex) or a BSDF (shade_surface). Each unit updates the PathState and says
// whether the path goes on.
RGB trace_path(const RenderScene& sc, Ray ray, int medium, Sampler& sampler, PathCounters& counters,
               const PathStart& start) {
  int own_split_budget = kSplitBudgetPerSample;
  PathContext ctx{sc, sampler, counters, start, start.split_budget ? *start.split_budget : own_split_budget};
  PathState st(ray, medium, start);
  const uint64_t last_stratified = start.first_dimension + kStratifiedVertices * kVertexDimensions;
  for (;; st.vertex_dimension += kVertexDimensions) {
    if (st.vertex_dimension < last_stratified)
      sampler.set_dimension(st.vertex_dimension);
    else
      sampler.set_dimension(st.vertex_dimension, 0);  // deep vertices: the sample's PCG32 stream
    SurfaceHit hit;
    counters.count(st.ray);
    const bool found = sc.embree->intersect(st.ray, hit);
    if (st.medium >= 0) {
      const VertexOutcome volume = shade_volume(ctx, st, found ? hit.t : kInfiniteDistance);
      if (volume == VertexOutcome::kStop) break;
      if (volume == VertexOutcome::kContinue) continue;
    }
    if (!found) {
      if (!st.emission_counted) add_emission_at_infinity(ctx, st);
      break;
    }
    const Shape& s = sc.shapes[hit.shape];
    if (s.first_light >= 0 && !st.emission_counted) add_area_emission(ctx, st, s, hit);
    st.emission_counted = false;
    if (!first_vertex_survives(ctx, st)) break;
    // A mix material resolves to one of its materials here, once per hit (material.h).
    const Material& mat = sc.materials[resolve_material(sc.materials, sc.textures, s.material, hit, -st.ray.d,
                                                        sampler.sample_hash(st.vertex_dimension))];
    if (mat.is_interface()) {
      // An index-matched boundary: change medium, keep going in the same direction.
      if (++st.crossings > kMaxInterfaceCrossings * 16) {
        ++counters.truncated;
        break;
      }
      st.medium = medium_after_crossing(s, st.ray.d, hit.ng, st.medium);
      st.ray.o = offset_ray_origin(hit.p, hit.ng, st.ray.d);
      st.ray.tmax = kInfiniteDistance;
      continue;
    }
    if (st.depth++ >= sc.settings.max_depth) break;
    const Vec3 wo = -st.ray.d;
    hit.ns = shading_normal_seen_from(hit, wo);  // geometry/shading_normal.h
    const VertexOutcome outcome = mat.type == Material::Type::Subsurface
                                      ? SubsurfaceVertex(ctx, st, hit, mat, wo).shade()
                                      : shade_surface(ctx, st, hit, s, mat, wo);
    if (outcome == VertexOutcome::kStop) break;
  }
  return st.L;
}

}  // namespace dermis
