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

// What a walk aims the plane of refraction at (refracted_light.h, the boundary facing it):
// the centre of the finite lights the walks sample, weighted by their power; where there
// are none, the mean direction of arrival of the environment maps' light when it comes
// mostly from one side (a sun, a bright window: kConcentratedArrival). Once per scene state.
struct KeyLight {
  Vec3 at;  // a point, or a unit direction toward the light when at_infinity
  bool at_infinity = false;
};
// The environment maps' mean direction of arrival is used from this length on (0 for light
// arriving evenly from every side, 1 for a single direction).
constexpr float kConcentratedArrival = 0.1f;
std::optional<KeyLight> key_light(const RenderScene& sc);
// The unit direction from y toward the key light; false where there is none.
bool key_light_direction(const std::optional<KeyLight>& key, Vec3 y, Vec3& toward);

}  // namespace dermis
