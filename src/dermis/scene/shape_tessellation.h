// Triangle meshes for pbrt's analytic shapes that Dermis renders as triangles.
#pragma once

#include <vector>

#include "dermis/scene/scene_desc.h"

namespace dermis {

// Segments per full turn of phi for the tessellated quadrics (disk, cylinder, partial
// sphere); a partial turn gets its share (at least 4). At 256 the chord of a segment
// lies at most r (1 - cos(pi/256)) = 7.5e-5 r inside the circle (docs/scene-format.md).
inline constexpr int kDiskSegments = 256;
inline constexpr int kSphereRows = 128;  // rings of a partial sphere over theta in [0, pi]
inline constexpr int kBilinearGrid = 8;  // non-planar bilinear patches: 8 x 8 quads each

// pbrt's disk at z = height, radius `radius`, hole `inner_radius` (0: none), over
// phi in [0, phimax_degrees], in object space: a fan of triangles around the centre, or a
// ring of quads. Wound counter-clockwise seen from +z, so the geometric normal is +z as
// for pbrt's disk; uv = (phi / phimax, (radius - r) / (radius - inner_radius)) as in
// pbrt; normals +z. `segments` is the count for a full turn.
TriangleMeshDesc tessellate_disk(float height, float radius, float inner_radius, int segments = kDiskSegments,
                                 float phimax_degrees = 360);

// pbrt's cylinder about the z axis: radius, z in [zmin, zmax], phi in [0, phimax]; open
// (no caps). Normals point away from the axis (pbrt's dp/du x dp/dv), uv = (phi / phimax,
// (z - zmin) / (zmax - zmin)); per-vertex normals are the exact ones.
TriangleMeshDesc tessellate_cylinder(float radius, float zmin, float zmax, float phimax_degrees,
                                     int segments = kDiskSegments);

// pbrt's sphere of `radius` cut to z in [zmin, zmax] (clamped to [-radius, radius]) and
// phi in [0, phimax]: theta from acos(zmin / r) down to acos(zmax / r). Outward normals
// (exact per vertex), uv = (phi / phimax, (theta - theta_zmin) / (theta_zmax - theta_zmin)),
// so v = 0 at zmin and 1 at zmax, as pbrt-v4. Poles (zmin = -r or zmax = r) are single
// points: the triangles there are not degenerate.
TriangleMeshDesc tessellate_sphere_part(float radius, float zmin, float zmax, float phimax_degrees,
                                        int segments = kDiskSegments, int rows = kSphereRows);

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
