// The camera's first smooth reflection, split off at a subsurface entry or at smooth glass:
// the reflection and the transmission are both followed, weighted F and 1 - F (unbiased:
// one sample of each term of F L_r + (1 - F) L_t). Chosen by Fresnel, a sharp highlight of
// a small light rests on the few per cent of samples that reflect (much of the image's
// error on a skin-like sphere: docs/rendering.md). Where the reflection cannot see a
// bright emitter it is
// rouletted on its weight (reflection_survival, path_state.h).
#pragma once

#include "dermis/core/rgb.h"
#include "dermis/geometry/ray.h"
#include "dermis/render/path/path_state.h"

namespace dermis {

// Whether the vertex the path is at (depth already counted) is the camera's first hit, where
// a smooth reflection is split off (EstimatorSwitches::split_first_hit, render_scene.h).
inline bool at_camera_first_hit(const PathContext& ctx, const PathState& st) {
  return ctx.sc.switches.split_first_hit && ctx.start.from_camera && ctx.start.depth == 0 && st.depth == 1;
}

// Traces the reflected path along reflected_ray (unless `reflects` is false: into the
// surface, no light) from its own sampler region, and adds weight x F / q x its radiance to
// st.L and to the pilot's record, q its survival probability (reflection_survival, with
// roulette_weight). The sampler is back at its dimension afterwards; the caller weighs the
// transmission by 1 - F.
void split_camera_reflection(PathContext& ctx, PathState& st, const Ray& reflected_ray, bool reflects,
                             const RGB& weight, float F, float roulette_weight);

}  // namespace dermis
