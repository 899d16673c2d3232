// A path's vertex at a surface with a BSDF (diffuse, glass, conductors, coated layers, ...):
// light sampling where the BSDF has a density (on both sides for diffuse transmission and
// rough glass), the camera's first reflection split off at smooth glass, a smooth
// reflection's bright emission counted, and the BSDF sampled for the way on (Cycles'
// shade_surface; pbrt-v4's VolPathIntegrator::Li at a surface, with SampleLd).
#pragma once

#include "dermis/geometry/ray.h"
#include "dermis/render/path/path_state.h"

namespace dermis {

// At `hit` on shape s with material mat, seen along wo = -st.ray.d (hit.ns already facing
// it; depth already counted). kContinue: the path goes on along st.ray; kStop: it ended.
// The BSDF bsdf_at made for `mat`, at a spectral path's wavelengths w: its RGB parameters as
// spectra (materials/at_wavelengths.h), and the parameters given as spectra (a named metal's
// eta and k, a reflectance or transmittance given as a named spectrum, a file or samples) as
// their own data.
BSDF material_bsdf_at_wavelengths(const RenderScene& sc, const Material& mat, BSDF bsdf, const SampledWavelengths& w);

VertexOutcome shade_surface(PathContext& ctx, PathState& st, const SurfaceHit& hit, const Shape& s, const Material& mat,
                            Vec3 wo);

}  // namespace dermis
