// A path's segment through a heterogeneous (grid) medium: a free flight by delta tracking
// over the medium's majorants (materials/null_scattering.h) that scatters, passes through or
// ends (absorbed); at a scattering event, next-event estimation with the shadow ray's
// transmittance by ratio tracking, and the phase function sampled for the way on (pbrt-v4's
// VolPathIntegrator::Li with SampleLd; Cycles' shade_volume, its heterogeneous part).
#pragma once

#include "dermis/render/path/path_state.h"

namespace dermis {

// st.ray traced to t_hit (infinity: no surface) in grid medium st.medium. kContinue: the path
// scattered and goes on along st.ray; kPassThrough: it reached t_hit; kStop: it ended.
VertexOutcome shade_grid_volume(PathContext& ctx, PathState& st, float t_hit);

}  // namespace dermis
