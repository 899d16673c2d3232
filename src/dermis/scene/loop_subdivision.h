// Loop subdivision surfaces (pbrt's "loopsubdiv" shape): C. Loop, "Smooth Subdivision
// Surfaces Based on Triangles", MSc thesis, University of Utah, 1987. A triangle mesh is
// refined a given number of times (each triangle into four), then every vertex is moved
// to its limit position on the smooth surface and given the limit surface's normal.
// Boundaries follow the cubic B-spline rules (Loop 1987; Hoppe et al., "Piecewise Smooth
// Surface Reconstruction", SIGGRAPH 1994, section 3), so an open mesh keeps its edges.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "dermis/core/load_monitor.h"
#include "dermis/core/vec.h"
#include "dermis/scene/scene_desc.h"

namespace dermis {

// A control mesh: 3 indices per triangle, consistently oriented, each edge shared by at
// most two triangles, each vertex's triangles one fan.
struct LoopMesh {
  std::vector<Vec3> positions;
  std::vector<uint32_t> indices;
};

// Called with the fraction of one pass over a mesh done (0 to 1, non-decreasing) every
// kLoopCheckEvery triangles or vertices; it may throw (Interrupted) to stop the pass.
using LoopProgress = std::function<void(double fraction)>;
inline constexpr std::size_t kLoopCheckEvery = 4096;

// One level of Loop's rules. The old vertices keep their indices (moved by the even
// rules); one new vertex per edge follows them; every triangle becomes four with its
// orientation. Throws std::invalid_argument (the message says where) for a mesh that is
// not a manifold as described above.
LoopMesh loop_refine(const LoopMesh& mesh, const LoopProgress& progress = {});

// The limit surface's point and unit normal for every vertex of `mesh` (normals on the
// side the triangles' winding, cross(p1 - p0, p2 - p0), points to).
std::vector<Vec3> loop_limit_positions(const LoopMesh& mesh, const LoopProgress& progress = {});
std::vector<Vec3> loop_limit_normals(const LoopMesh& mesh, const LoopProgress& progress = {});

// The most triangles loop_subdivision_surface makes (levels beyond are refused).
inline constexpr std::size_t kMaxLoopTriangles = std::size_t(1) << 25;

// `levels` refinements, then limit positions and normals: pbrt-v4's "loopsubdiv".
// Throws std::invalid_argument for a non-manifold mesh or too many triangles. With a
// monitor: stage "subdividing (loopsubdiv)", reported by the triangles made so far and
// checked for cancellation (Interrupted) every kLoopCheckEvery triangles or vertices,
// inside a level too.
TriangleMeshDesc loop_subdivision_surface(const std::vector<Vec3>& positions, const std::vector<uint32_t>& indices,
                                          int levels, const LoadMonitor* monitor = nullptr);

}  // namespace dermis
