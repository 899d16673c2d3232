#include "dermis/render/path/grid_volume_vertex.h"

#include "dermis/materials/null_scattering.h"
#include "dermis/render/path/volume_vertex.h"
#include "dermis/render/russian_roulette.h"
#include "dermis/render/spectral_media.h"

namespace dermis {

VertexOutcome shade_grid_volume(PathContext& ctx, PathState& st, float t_hit) {
  const RenderScene& sc = ctx.sc;
  Sampler& sampler = ctx.sampler;
  const GridMediumView m = grid_medium_view(sc, st.medium, st.wavelengths, true);
  // The flight's channel follows the throughput times the medium's preference.
  const RGB preference = m.channel_preference();
  const Vec2 u_flight = sampler.get2d();
  Rng rng = tracking_rng(u_flight.y, st.ray);
  const NullScatteringFlight flight =
      sample_null_scattering_flight(m, st.ray, t_hit, st.beta, preference, u_flight.x, rng, Absorption::Weighted);
  if (st.depth < sc.settings.max_depth) st.L += st.beta * flight.emitted;  // as pbrt-v4, below the depth limit
  if (flight.stalled) ++ctx.counters.truncated;
  if (!flight.valid) return VertexOutcome::kStop;
  st.beta *= flight.weight;
  if (!st.beta.is_finite() || st.beta.is_black()) return VertexOutcome::kStop;
  if (!flight.scattered) return VertexOutcome::kPassThrough;  // to the surface (or to infinity)

  // A scattering event in the medium.
  if (!first_vertex_survives(ctx, st)) return VertexOutcome::kStop;
  const Vec3 p = st.ray.o + st.ray.d * flight.t;
  if (st.depth++ >= sc.settings.max_depth) return VertexOutcome::kStop;
  const float g = m.g;
  const bool sees_lights = sc.medium_sees_lights[st.medium];
  if (sees_lights) st.L += st.beta * direct_by_phase(ctx, st, p, g);
  return scatter_by_phase(ctx, st, p, g, sees_lights);
}

}  // namespace dermis
