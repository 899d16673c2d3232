#include "dermis/render/path/volume_vertex.h"

#include "dermis/core/henyey_greenstein.h"
#include "dermis/materials/free_flight.h"
#include "dermis/render/path/direct_light.h"
#include "dermis/render/path/grid_volume_vertex.h"
#include "dermis/render/russian_roulette.h"
#include "dermis/render/spectral_media.h"

namespace dermis {

VertexOutcome shade_volume(PathContext& ctx, PathState& st, float t_hit) {
  const RenderScene& sc = ctx.sc;
  if (sc.grid_medium_of(st.medium) >= 0) return shade_grid_volume(ctx, st, t_hit);
  Sampler& sampler = ctx.sampler;
  const HomogeneousMedium& m = st.medium_of(sc, st.medium);
  const MediumSegment segment = medium_segment(m, t_hit);
  if (st.depth < sc.settings.max_depth) {
    // The medium's emission over the whole segment in closed form, whatever the flight does:
    // int_0^t_max T(t) sigma_a Le dt = sigma_a Le (1 - T(t_max)) / sigma_t (pbrt-v4 sec. 11.1.1, eq. 11.6).
    const RGB Le = homogeneous_emission(sc, st.medium, st.wavelengths);
    for (int c = 0; c < 3; ++c)
      if (Le[c] > 0 && m.sigma_t[c] > 0)
        st.L[c] += st.beta[c] * m.sigma_a[c] * Le[c] * segment.captured[c] / m.sigma_t[c];
  }
  // The free flight's channel and distance, jointly stratified.
  const Vec2 u_flight = sampler.get2d();
  // Direct light in-scattered anywhere on the segment, at a point drawn for it alone
  // (decoupled from the free flight below, as Cycles' volume integrator does): the path
  // gathers it also where it passes through, and its scattering events do no next-event
  // estimation of their own. A path that finds a light by phase sampling weighs itself
  // against this estimate at its own scattering point: the two weights sum to one at every
  // point, so any distance distribution of either strategy keeps the sum unbiased.
  // The point takes the free flight's distance number u (its channel has a number of its
  // own). In the flight's channel, where the flight scatters at t_s the point, the
  // truncated exponential's quantile at u (1 - T(t_max)), lies on [0, t_s], the stretch the
  // path travels; where it passes through, toward the segment's end. Both are drawn on
  // every segment whatever the other's outcome, so the light sample keeps its exact
  // distribution on its segment and the path its own: the sum stays unbiased (the
  // expectation of a sum is the sum of the expectations, however the terms correlate).
  // Against an independent number for the point: docs/results/results-rendering.md, "Direct light in a medium".
  const float u_segment_channel = sampler.get1d();
  const bool sees_lights = sc.medium_sees_lights[st.medium];
  if (sees_lights && st.depth < sc.settings.max_depth) {
    const SegmentPoint sp = sample_segment_point(m, segment, st.beta, u_segment_channel, u_flight.y);
    if (sp.valid) {
      st.L += st.beta * sp.weight * direct_by_phase(ctx, st, st.ray.o + st.ray.d * sp.t, m.g);
    } else {
      sampler.get2d();  // the light sample's two dimensions, so that those after it do not shift
    }
  } else if (sees_lights) {
    sampler.get2d();
  }
  const FreeFlight flight = sample_free_flight(m, segment, st.beta, u_flight.x, u_flight.y);
  if (!flight.valid) return VertexOutcome::kStop;
  st.beta *= flight.weight;
  if (!st.beta.is_finite() || st.beta.is_black()) return VertexOutcome::kStop;
  if (!flight.scattered) return VertexOutcome::kPassThrough;  // to the surface (or to infinity)

  // A scattering event in the medium.
  if (!first_vertex_survives(ctx, st)) return VertexOutcome::kStop;
  const Vec3 p = st.ray.o + st.ray.d * flight.t;
  if (st.depth++ >= sc.settings.max_depth) return VertexOutcome::kStop;
  const float g = m.g;
  return scatter_by_phase(ctx, st, p, g, sees_lights);
}

RGB direct_by_phase(PathContext& ctx, const PathState& st, Vec3 p, float g) {
  const Vec3 wo = -st.ray.d;
  return estimate_direct(ctx.sc, p, Vec3(0, 0, 0), st.medium, ctx.sampler, ctx.counters, ctx.start.wavelengths,
                         [&](Vec3 wi) {
                           const float ph = henyey_greenstein(dot(-wo, wi), g);
                           return std::pair{RGB(ph), ph};
                         });
}

VertexOutcome scatter_by_phase(PathContext& ctx, PathState& st, Vec3 p, float g, bool sees_lights) {
  // Sample the phase function about the propagation direction (weight 1).
  const Vec2 u_phase = ctx.sampler.get2d();
  const float cos_theta = sample_henyey_greenstein_cos(u_phase.x, g);
  const Vec3 wi = direction_about(st.ray.d, cos_theta, u_phase.y);
  st.camera_chain = false;
  st.after_scatter(Ray{p, wi}, henyey_greenstein(cos_theta, g), p, Vec3(0, 0, 0), SkyRule::Sampled, false);
  if (!survives_roulette(ctx, st, sees_lights ? kMediumRouletteThreshold : kSurfaceRouletteThreshold))
    return VertexOutcome::kStop;
  return VertexOutcome::kContinue;
}

}  // namespace dermis
