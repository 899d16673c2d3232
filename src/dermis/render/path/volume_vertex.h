// A path's segment through a homogeneous medium, up to the surface it was traced to (or to
// infinity): the light in-scattered along the segment, and the free flight that either
// scatters in the medium (the phase function sampled for the way on) or passes through
// (Cycles' shade_volume; pbrt-v4's VolPathIntegrator::Li, its medium part).
#pragma once

#include "dermis/render/path/path_state.h"

namespace dermis {

// st.ray traced to t_hit (infinity: no surface) in medium st.medium. kContinue: the path
// scattered and goes on along st.ray; kPassThrough: it reached t_hit; kStop: it ended.
VertexOutcome shade_volume(PathContext& ctx, PathState& st, float t_hit);

// Next-event estimation at p in the path's medium of Henyey-Greenstein g, phase function
// times light over their MIS (path/direct_light.h estimate_direct).
RGB direct_by_phase(PathContext& ctx, const PathState& st, Vec3 p, float g);

// After a scattering event at p in a medium of Henyey-Greenstein g (next-event estimation
// done): the phase function sampled for the way on, and the roulette. kContinue or kStop.
VertexOutcome scatter_by_phase(PathContext& ctx, PathState& st, Vec3 p, float g, bool sees_lights);

}  // namespace dermis
