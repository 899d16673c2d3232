// A triangulated sphere, for shapes that must be triangles (ellipsoids, point
// distribution over a sphere).
#pragma once

#include <cstdint>
#include <vector>

#include "dermis/core/vec.h"

namespace dermis {

// A sphere of `radius` about the origin: (2n x n) quads in latitude/longitude, outward winding.
void tessellate_sphere(float radius, int n, std::vector<Vec3>& positions, std::vector<uint32_t>& indices);

}  // namespace dermis
