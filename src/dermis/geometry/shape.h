// Shapes as the renderer holds them: triangle meshes in world space (or in an
// instanced object's space), exact spheres, and curves (Embree's curve primitives).
#pragma once

#include <cstdint>
#include <vector>

#include "dermis/core/rgb.h"
#include "dermis/core/transform.h"
#include "dermis/core/vec.h"

namespace dermis {

struct Shape {
  enum class Type { Mesh, Sphere, Curve };
  // Curve: how its cross-section is traced (pbrt-v4's curve "type"): a band facing the
  // ray, a round tube, or a band oriented by per-point normals.
  enum class CurveKind { Flat, Cylinder, Ribbon };
  Type type = Type::Mesh;
  // Mesh: vertices in the space of the Embree scene that holds it. Curve: cubic Bézier
  // control points, 4 per segment (segment k: positions[4k .. 4k+3]); indices stay empty.
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;       // mesh: optional per-vertex shading normals; ribbon curve: per control point
  std::vector<float> curve_radii;  // curve: half the width at each control point
  CurveKind curve_kind = CurveKind::Flat;
  std::vector<Vec2> uvs;  // optional
  std::vector<uint32_t> indices;
  // Sphere: centre and radius in the space of the Embree scene that holds it.
  Vec3 center;
  float radius = 0;
  // Flip the geometric normal (pbrt: ReverseOrientation xor handedness swap).
  bool flip_normals = false;
  int material = -1;  // index into RenderScene::materials
  int inside_medium = -1, outside_medium = -1;
  bool has_medium_interface = false;
  int first_light = -1;  // index of the area light of its first primitive, -1 if not emissive
  int instance = -1;     // instance index when the shape belongs to an instanced object
  // Alpha cut-out (geometry/alpha_mask.h): a constant, or a float texture (-1: none).
  float alpha = 1;
  int alpha_texture = -1;
  bool has_alpha() const { return alpha < 1 || alpha_texture >= 0; }

  std::size_t primitive_count() const {
    return type == Type::Sphere ? 1 : type == Type::Curve ? positions.size() / 4 : indices.size() / 3;
  }

  // Oriented unit geometric normal of triangle `prim` at barycentrics (b1, b2), in the
  // shape's own space (pbrt-v4's rule: with vertex normals the geometric normal
  // takes their side, otherwise flip_normals decides). Also returns the shading normal.
  Vec3 triangle_normal(int prim, float b1, float b2, Vec3* shading = nullptr) const {
    const uint32_t* tri = &indices[3 * std::size_t(prim)];
    const Vec3 &p0 = positions[tri[0]], &p1 = positions[tri[1]], &p2 = positions[tri[2]];
    Vec3 ng = normalize(cross(p0 - p2, p1 - p2));
    Vec3 ns = ng;
    if (!normals.empty()) {
      float b0 = 1 - b1 - b2;
      Vec3 n = normals[tri[0]] * b0 + normals[tri[1]] * b1 + normals[tri[2]] * b2;
      if (length_squared(n) > 0) {
        ns = normalize(n);
        ng = face_forward(ng, ns);
      } else if (flip_normals) {
        ng = -ng;
        ns = ng;
      }
    } else if (flip_normals) {
      ng = -ng;
      ns = ng;
    }
    if (shading) *shading = ns;
    return ng;
  }
};

}  // namespace dermis
