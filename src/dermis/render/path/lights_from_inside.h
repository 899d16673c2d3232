// The scene's lights as a walk inside a subsurface object sees them, for light sampled
// through its smooth boundary (subsurface/refracted_light.h): a direction toward a light
// drawn as next-event estimation in a medium draws it (the light selection at the point,
// then a point or direction on the light), the density of any direction under that
// drawing, and the emission met along a direction from the boundary.
#pragma once

#include <optional>

#include "dermis/core/rgb.h"
#include "dermis/core/vec.h"
#include "dermis/render/path_counters.h"
#include "dermis/render/render_scene.h"

namespace dermis {

// Whether the integrator offers the lights to walks in an object surrounded by
// `outside_medium`: in vacuum, without index-matched interfaces (the emission is the first
// surface's along a direction) and with few lights (the density sums over them), none of
// them a sphere lit inward, and one at least that the walks sample (an area light or an
// environment map: not delta lights, not uniform skies).
bool lights_offered_inside(const RenderScene& sc, int outside_medium);

// A direction w toward a light from y (u1 chooses the light, u2 and u1's remainder place
// the sample), with the density of drawing it; false: none (delta lights are never drawn).
bool sample_light_from_inside(const RenderScene& sc, Vec3 y, float u1, float u2, Vec3& w, float& density);

// The solid-angle density with which sample_light_from_inside draws w from y: over every
// light along w (whether or not something lies between), its probability of being chosen
// times its density.
float light_density_from_inside(const RenderScene& sc, Vec3 y, Vec3 w);

// The centre of the finite lights the walks sample, weighted by their power (once per
// scene state); none where there are none.
std::optional<Vec3> key_light_centre(const RenderScene& sc);
// The unit direction from y toward that centre; false where there is none.
bool key_light_direction(const std::optional<Vec3>& centre, Vec3 y, Vec3& toward);

}  // namespace dermis
