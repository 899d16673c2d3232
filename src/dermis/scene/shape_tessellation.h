// Triangle meshes for pbrt's analytic shapes that Dermis renders as triangles.
#pragma once

#include <vector>

#include "dermis/scene/scene_desc.h"

namespace dermis {

inline constexpr int kDiskSegments = 256;
inline constexpr int kBilinearGrid = 8;  // non-planar bilinear patches: 8 x 8 quads each

// pbrt's disk at z = height, radius `radius`, hole `inner_radius` (0: none), in object
// space: a fan of `segments` triangles around the centre, or a ring of 2*segments
// triangles. Wound counter-clockwise seen from +z, so the geometric normal is +z as for
// pbrt's disk; uv = (phi / 2pi, (radius - r) / (radius - inner_radius)) as in pbrt; normals +z.
TriangleMeshDesc tessellate_disk(float height, float radius, float inner_radius, int segments = kDiskSegments);

// pbrt's bilinear patches: 4 vertices per patch in the order p00, p10, p01, p11, with
// p(u,v) = (1-u)(1-v) p00 + u(1-v) p10 + (1-u)v p01 + uv p11. A planar patch (p11 within
// 1e-6 of the patch size of the plane of the other three) becomes the two triangles
// (p00,p10,p11), (p00,p11,p01), whose normal is dp/du x dp/dv as pbrt's; any other patch
// is evaluated on a grid of kBilinearGrid x kBilinearGrid quads (2 triangles each).
// `uv` and `normals` are per vertex (may be empty) and are interpolated bilinearly.
// `indices` has 4 entries per patch and has been range-checked.
TriangleMeshDesc tessellate_bilinear_patches(const std::vector<Vec3>& positions, const std::vector<uint32_t>& indices,
                                             const std::vector<Vec2>& uv, const std::vector<Vec3>& normals);

}  // namespace dermis
