// Ray queries restricted to one surface object, for subsurface scattering: all the
// hits of a probe segment on the object, and the first boundary hit of a ray
// travelling inside it.
#pragma once

#include <vector>

#include "dermis/geometry/ray.h"
#include "dermis/render/render_scene.h"
#include "dermis/render/integrator.h"

namespace dermis {

// Appends to `hits` every intersection of the segment o + t d, t in (0, length), with
// the object of `object` (same shape and instance), in order, at most max_hits.
void collect_object_hits(const RenderScene& sc, const SurfaceHit& object, Vec3 o, Vec3 d, float length, int max_hits,
                         std::vector<SurfaceHit>& hits, PathCounters& counters);

// The first intersection of the ray with the object of `object`, skipping other shapes.
bool first_object_hit(const RenderScene& sc, const SurfaceHit& object, Ray ray, SurfaceHit& hit,
                      PathCounters& counters);

}  // namespace dermis
