// The mean chord length of a closed object, 4 V / S (Cauchy's formula: the mean length
// of the chords that uniformly and isotropically distributed lines cut from a convex body;
// for a non-convex one the mean of the chord segments inside it): a sphere of diameter D
// gives 2D/3, a slab of thickness t and large faces 2t. Its thickness as a walk sees it.
#pragma once

#include <vector>

#include "dermis/geometry/shape.h"

namespace dermis {

// Over the given shapes, taken as one object: meshes (their volume by the divergence
// theorem, V = sum over triangles of p0 . (p1 x p2) / 6, and their area) and spheres;
// curves have no volume and are skipped. 0 where a mesh is open (the sum of its faces'
// oriented area vectors exceeds kClosedSurfaceTolerance of their area: an open surface
// may give any volume, and its 4V/S is no thickness) or where the volume or the area is
// not positive and finite.
inline constexpr double kClosedSurfaceTolerance = 1e-3;
double mean_chord_length(const std::vector<const Shape*>& shapes);

}  // namespace dermis
