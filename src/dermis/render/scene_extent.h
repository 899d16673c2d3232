// The range of world coordinates the renderer accepts. Embree refuses (asserts on) rays
// whose origin lies beyond about 1.8e18 in any coordinate, and 32-bit floats that far out
// have no precision left; a scene reaching there (a camera at 1e19, a sphere of radius
// 1e30) is reported at its directive instead of aborting the render.
#pragma once

#include <string_view>

#include "dermis/core/transform.h"
#include "dermis/core/vec.h"
#include "dermis/geometry/shape.h"
#include "dermis/scene/diagnostics.h"

namespace dermis {

// The largest absolute world coordinate allowed, with margin below Embree's 1.844e18.
inline constexpr float kMaxSceneCoordinate = 1e17f;

// Throws SceneError at `loc` ("<what> lies at (x, y, z), beyond ...") when a coordinate of
// `p` is not finite or beyond kMaxSceneCoordinate.
void check_scene_point(const Vec3& p, const SourceLoc& loc, std::string_view what);

// Checks every vertex of a mesh, or a sphere's bounding box, after `to_world` (identity
// for shapes already in world space; an instance's transform for an object's shapes).
void check_shape_extent(const Shape& s, const Transform& to_world, const SourceLoc& loc);

// The box [lo, hi] (an instanced object's bounds) after `to_world`: its eight corners.
void check_box_extent(const Vec3& lo, const Vec3& hi, const Transform& to_world, const SourceLoc& loc,
                      std::string_view what);

}  // namespace dermis
