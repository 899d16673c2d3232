// Emission a path meets: at a light's surface or from the lights at infinity, weighed
// against the light sampling of the path's last scattering event (MIS, power heuristic), and
// a smooth reflection's bright emission counted at every hit (add_bright_emission_seen).
#pragma once

#include "dermis/core/rgb.h"
#include "dermis/geometry/ray.h"
#include "dermis/render/path/path_state.h"
#include "dermis/render/path_counters.h"
#include "dermis/render/render_scene.h"

namespace dermis {

// The lights at infinity seen along st.ray (which met no surface), added to st.L.
void add_emission_at_infinity(const PathContext& ctx, PathState& st);

// The emission of the area light of shape s, met at `hit` along st.ray, added to st.L.
void add_area_emission(const PathContext& ctx, PathState& st, const Shape& s, const SurfaceHit& hit);

// The emission `ray` meets at its first surface, or from the lights at infinity where it
// meets none, in full (as after a specular bounce). In vacuum: no transmittance. At the
// path's wavelengths when it has them (null: RGB); `rgb`, if given, receives it in RGB.
RGB emission_seen(const RenderScene& sc, const Ray& ray, PathCounters& counters, const SampledWavelengths* wavelengths,
                  RGB* rgb = nullptr);

// The mean luminance of the lights at infinity over the sphere of directions.
float mean_sky_luminance(const RenderScene& sc);

// Whether the emission `ray` meets may be brighter than twice the mean sky, known without
// tracing it: only where it may meet a finite emitter (LightSelection's bounds) or the
// lights at infinity are that bright along it (a uniform sky never is).
bool may_see_bright_emission(const RenderScene& sc, const Ray& ray);

// Adds weight x the emission `ray` meets (emission_seen) to L where it is brighter than
// twice the mean sky, and says whether it did: a smooth reflection's emission counted at
// every hit, a reflected path then going on without it (at subsurface entries and smooth
// glass). Any rule that looks at the emission alone keeps the estimate unbiased. Where it
// cannot be that bright (may_see_bright_emission) the ray is not traced: the same result.
bool add_bright_emission_seen(const RenderScene& sc, const Ray& ray, RGB weight, PathCounters& counters,
                              const SampledWavelengths* wavelengths, RGB& L);

}  // namespace dermis
