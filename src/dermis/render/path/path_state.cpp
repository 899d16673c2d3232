#include "dermis/render/path/path_state.h"

#include "dermis/render/path/emission.h"
#include "dermis/render/path/sampler_regions.h"
#include "dermis/render/russian_roulette.h"
#include "dermis/render/spectral_media.h"

namespace dermis {

PathState::PathState(const Ray& r, int m, const PathStart& start)
    : ray(r),
      medium(m),
      specular(start.from_camera || start.prev_specular),
      prev_pdf(start.prev_pdf),
      prev_p(start.from_camera ? r.o : start.prev_p),
      prev_n(start.from_camera ? Vec3(0, 0, 0) : start.prev_n),
      prev_sky(start.from_camera ? SkyRule::Sampled : start.prev_sky),
      emission_weight(start.prev_emission_weight),
      depth(start.depth),
      camera_chain(start.from_camera && start.depth == 0),
      vertex_dimension(start.first_dimension),
      wavelengths(start.wavelengths) {}

const HomogeneousMedium& PathState::medium_of(const RenderScene& sc, int m) const {
  if (m == entered_medium) return entered;
  if (!wavelengths) return sc.media[m];
  if (converted_index_ != m) {
    converted_ = scene_medium_at_wavelengths(sc, m, *wavelengths);
    converted_index_ = m;
  }
  return converted_;
}

bool survives_roulette(PathContext& ctx, PathState& st, float threshold) {
  if (st.depth <= 1) return true;
  const float p = roulette_survival(st.beta.max() * st.eta_scale, threshold);
  if (p >= 1) return true;
  if (!(ctx.sampler.get1d() < p)) return false;
  st.beta /= p;
  return true;
}

bool first_vertex_survives(PathContext& ctx, PathState& st) {
  if (!st.first_vertex) return true;
  st.first_vertex = false;
  if (!(ctx.start.first_vertex_roulette > 0)) return true;
  const float q = roulette_survival(ctx.start.first_vertex_roulette, kSurfaceRouletteThreshold);
  if (q >= 1) return true;
  const Sampler::Position resume = ctx.sampler.position();
  ctx.sampler.set_dimension(Sampler::region(ctx.start.first_dimension, kReflectionRouletteRegion));
  const bool survives = ctx.sampler.get1d() < q;
  ctx.sampler.restore(resume);
  if (survives) st.beta /= q;
  return survives;
}

float reflection_survival(PathContext& ctx, const PathState& st, const Ray& reflected_ray, float weight,
                          PathStart& reflected) {
  if (!ctx.sc.switches.reflection_roulette || may_see_bright_emission(ctx.sc, reflected_ray)) return 1.0f;
  const float rr = st.beta.max() * st.eta_scale * weight;
  if (mean_sky_luminance(ctx.sc) > 0) {
    reflected.first_vertex_roulette = rr;
    return 1.0f;
  }
  const float q = roulette_survival(rr, kSurfaceRouletteThreshold);
  if (q >= 1) return 1.0f;
  ctx.sampler.set_dimension(Sampler::region(ctx.sampler.dimension(), kReflectionRouletteRegion));
  return ctx.sampler.get1d() < q ? q : 0.0f;
}

PathStart continuation(const PathStart& parent, int depth, uint64_t first_dimension, int& split_budget) {
  PathStart next;
  next.from_camera = false;
  next.depth = depth;
  next.first_dimension = first_dimension;
  next.subsurface_strategies = parent.subsurface_strategies;
  next.split_budget = &split_budget;
  next.wavelengths = parent.wavelengths;
  return next;
}

}  // namespace dermis
