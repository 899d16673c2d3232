// Shading normals: the interpolated vertex normal SurfaceHit::ns shapes the BSDF (its
// frame and cosines, as in pbrt-v4 and Cycles), while the geometric normal ng keeps
// deciding where light goes (ray offsets, the medium a crossing enters, emission sides).
// Where the two disagree about a direction's side, the direction would reflect into the
// surface or refract out of it; the BSDF is taken as zero there, for light-sampled and
// BSDF-sampled directions alike, so that MIS sees one function (Mitsuba's "strict
// normals"; Veach 1997, sec. 5.3, on what shading normals break).
#pragma once

#include "dermis/core/vec.h"
#include "dermis/geometry/ray.h"

namespace dermis {

// Whether direction w is on the same side of the shading normal as of the geometric one.
inline bool shading_side_agrees(Vec3 ng, Vec3 ns, Vec3 w) { return dot(w, ng) * dot(w, ns) > 0; }
inline bool shading_side_agrees(const SurfaceHit& hit, Vec3 w) { return shading_side_agrees(hit.ng, hit.ns, w); }

// The shading normal to use for a vertex seen from wo: ns, or ng where wo sees the back of
// the shading hemisphere (near the silhouette of a coarse smooth-shaded mesh), where the
// shading normal would make the surface face away from the direction it is seen from.
inline Vec3 shading_normal_seen_from(const SurfaceHit& hit, Vec3 wo) {
  return shading_side_agrees(hit, wo) ? hit.ns : hit.ng;
}

}  // namespace dermis
