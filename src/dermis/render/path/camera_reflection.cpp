#include "dermis/render/path/camera_reflection.h"

#include "dermis/render/path/sampler_regions.h"

namespace dermis {

void split_camera_reflection(PathContext& ctx, PathState& st, const Ray& reflected_ray, bool reflects,
                             const RGB& weight, float F, float roulette_weight) {
  const uint64_t resume = ctx.sampler.dimension();
  // After a specular bounce: emission counts in full.
  PathStart reflected =
      continuation(ctx.start, st.depth, Sampler::region(resume, kReflectedPathRegion), ctx.split_budget);
  reflected.prev_specular = true;
  if (const float q = reflects ? reflection_survival(ctx, st, reflected_ray, roulette_weight, reflected) : 0.0f;
      q > 0) {
    const RGB Lr =
        weight * (F / q) * trace_path(ctx.sc, reflected_ray, st.medium, ctx.sampler, ctx.counters, reflected);
    st.L += Lr;
    if (ctx.start.subsurface_record) ctx.start.subsurface_record->camera_reflection += Lr;
  }
  ctx.sampler.set_dimension(resume);
}

}  // namespace dermis
