// A ray and the surface hit record the renderer works with.
#pragma once

#include <limits>

#include "dermis/core/vec.h"

namespace dermis {

struct Ray {
  Vec3 o, d;
  float tmax = std::numeric_limits<float>::infinity();
};

// Where a ray met a surface, in world space.
struct SurfaceHit {
  float t = 0;
  Vec3 p;             // position
  Vec3 ng;            // geometric normal, unit, oriented as the shape says "outside"
  Vec3 ns;            // shading normal (interpolated vertex normals), unit, same side as ng
  Vec2 uv;            // surface parameterisation (texture coordinates)
  int shape = -1;     // index into RenderScene::shapes
  int prim = -1;      // triangle index within the shape
  int instance = -1;  // object instance the shape was hit through, -1 for top-level shapes
};

// Offsets a ray origin off a surface, to the side of direction w, so that the
// new ray does not find the surface it starts on again.
// The distance a ray leaving a surface point p keeps from it (relative to |p|, at least 1e-4).
inline float surface_offset(Vec3 p) { return 1e-4f * std::max(1.0f, max_component(abs(p))); }

inline Vec3 offset_ray_origin(Vec3 p, Vec3 ng, Vec3 w) {
  float scale = surface_offset(p);
  return p + (dot(w, ng) > 0 ? ng : -ng) * scale;
}

}  // namespace dermis
