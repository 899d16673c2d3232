#include "dermis/scene/shape_tessellation.h"

#include <algorithm>
#include <cmath>

namespace dermis {

namespace {

// A surface p(u, v) over the unit square as a grid of nu x nv quads, two triangles each,
// wound so that the geometric normal is dp/du x dp/dv. Rows whose points all coincide
// (`pole_row`: a disk's centre, a sphere's pole) keep their nu + 1 vertices (u differs)
// but lose the triangles that would be degenerate there.
template <class Eval>
TriangleMeshDesc parametric_grid(int nu, int nv, Eval eval, bool pole_row_0, bool pole_row_nv) {
  TriangleMeshDesc m;
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) {
      const float u = float(i) / float(nu), v = float(j) / float(nv);
      Vec3 p, n;
      eval(u, v, p, n);
      m.positions.push_back(p);
      m.normals.push_back(n);
      m.uvs.emplace_back(u, v);
    }
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      uint32_t a = uint32_t(j * (nu + 1) + i), b = a + 1, c = a + uint32_t(nu + 1), d = c + 1;
      if (!(j == 0 && pole_row_0)) m.indices.insert(m.indices.end(), {a, b, d});  // a=(u,v) b=(u+,v) c=(u,v+)
      if (!(j == nv - 1 && pole_row_nv)) m.indices.insert(m.indices.end(), {a, d, c});
    }
  return m;
}

// Segments for phi in [0, phimax] when a full turn has `segments`.
int arc_segments(float phimax_radians, int segments) {
  return std::max(4, int(std::ceil(float(segments) * phimax_radians / (2 * kPi) - 1e-4f)));
}

}  // namespace

static float clamped_phimax_radians(float phimax_degrees) {
  return std::clamp(phimax_degrees, 0.0f, 360.0f) * kPi / 180;
}

TriangleMeshDesc tessellate_disk(float height, float radius, float inner_radius, int segments, float phimax_degrees) {
  const float phimax = clamped_phimax_radians(phimax_degrees);
  // pbrt-v4 disk: r = radius - v (radius - inner) at phi = u phimax, z = height.
  auto eval = [&](float u, float v, Vec3& p, Vec3& n) {
    const float r = v == 1 ? inner_radius : radius - v * (radius - inner_radius);
    const float phi = u * phimax;
    p = Vec3(r * std::cos(phi), r * std::sin(phi), height);
    n = Vec3(0, 0, 1);
  };
  return parametric_grid(arc_segments(phimax, segments), 1, eval, false, inner_radius == 0);
}

TriangleMeshDesc tessellate_cylinder(float radius, float zmin, float zmax, float phimax_degrees, int segments) {
  const float phimax = clamped_phimax_radians(phimax_degrees);
  const float z0 = std::min(zmin, zmax), z1 = std::max(zmin, zmax);
  auto eval = [&](float u, float v, Vec3& p, Vec3& n) {
    const float phi = u * phimax, c = std::cos(phi), s = std::sin(phi);
    p = Vec3(radius * c, radius * s, v == 1 ? z1 : z0 + v * (z1 - z0));
    n = Vec3(c, s, 0);
  };
  return parametric_grid(arc_segments(phimax, segments), 1, eval, false, false);
}

TriangleMeshDesc tessellate_sphere_part(float radius, float zmin, float zmax, float phimax_degrees, int segments,
                                        int rows) {
  const float phimax = clamped_phimax_radians(phimax_degrees);
  const float z0 = std::clamp(std::min(zmin, zmax), -radius, radius);
  const float z1 = std::clamp(std::max(zmin, zmax), -radius, radius);
  const float theta0 = std::acos(std::clamp(z0 / radius, -1.0f, 1.0f));  // theta at zmin (larger)
  const float theta1 = std::acos(std::clamp(z1 / radius, -1.0f, 1.0f));
  const bool pole0 = z0 <= -radius, pole1 = z1 >= radius;
  const int nv = std::max(1, int(std::ceil(float(rows) * (theta0 - theta1) / kPi - 1e-4f)));
  auto eval = [&](float u, float v, Vec3& p, Vec3& n) {
    const float phi = u * phimax;
    if ((v == 0 && pole0) || (v == 1 && pole1)) {
      n = Vec3(0, 0, v == 0 ? -1.0f : 1.0f);
    } else {
      const float theta = v == 1 ? theta1 : theta0 + v * (theta1 - theta0);
      const float st = std::sin(theta);
      n = Vec3(st * std::cos(phi), st * std::sin(phi), std::cos(theta));
    }
    p = n * radius;
    if (v == 0) p.z = pole0 ? -radius : z0;  // the cut planes exactly where pbrt puts them
    if (v == 1) p.z = pole1 ? radius : z1;
  };
  return parametric_grid(arc_segments(phimax, segments), nv, eval, pole0, pole1);
}

namespace {

template <class T>
T bilerp(const T& p00, const T& p10, const T& p01, const T& p11, float u, float v) {
  return p00 * ((1 - u) * (1 - v)) + p10 * (u * (1 - v)) + p01 * ((1 - u) * v) + p11 * (u * v);
}

bool is_planar(Vec3 p00, Vec3 p10, Vec3 p01, Vec3 p11) {
  Vec3d a(p00), b(p10), c(p01), d(p11);
  double size = std::max({length(b - a), length(c - a), length(d - a), 1e-30});
  Vec3d n = cross(b - a, c - a);
  double nl = length(n);
  if (nl < 1e-12 * size * size) return true;  // degenerate: no better than two triangles
  return std::abs(dot(d - a, n / nl)) <= 1e-6 * size;
}

}  // namespace

TriangleMeshDesc tessellate_bilinear_patches(const std::vector<Vec3>& positions, const std::vector<uint32_t>& indices,
                                             const std::vector<Vec2>& uv, const std::vector<Vec3>& normals) {
  TriangleMeshDesc m;
  const bool has_uv = !uv.empty(), has_n = !normals.empty();
  for (size_t q = 0; q + 3 < indices.size(); q += 4) {
    const uint32_t i00 = indices[q], i10 = indices[q + 1], i01 = indices[q + 2], i11 = indices[q + 3];
    // Default uv of pbrt's bilinear patch: the patch's own (u, v).
    Vec2 t00 = has_uv ? uv[i00] : Vec2(0, 0), t10 = has_uv ? uv[i10] : Vec2(1, 0);
    Vec2 t01 = has_uv ? uv[i01] : Vec2(0, 1), t11 = has_uv ? uv[i11] : Vec2(1, 1);
    const Vec3 &p00 = positions[i00], &p10 = positions[i10], &p01 = positions[i01], &p11 = positions[i11];
    const uint32_t base = uint32_t(m.positions.size());
    const int n = is_planar(p00, p10, p01, p11) ? 1 : kBilinearGrid;
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        float u = float(i) / float(n), v = float(j) / float(n);
        m.positions.push_back(bilerp(p00, p10, p01, p11, u, v));
        m.uvs.push_back(bilerp(t00, t10, t01, t11, u, v));
        if (has_n) {
          Vec3 nn = bilerp(normals[i00], normals[i10], normals[i01], normals[i11], u, v);
          float l = length(nn);
          m.normals.push_back(l > 0 ? nn / l : nn);
        }
      }
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        uint32_t a = base + j * (n + 1) + i, b = a + 1, c = a + (n + 1), d = c + 1;  // a=(u,v) b=(u+,v) c=(u,v+)
        m.indices.insert(m.indices.end(), {a, b, d, a, d, c});
      }
  }
  return m;
}

}  // namespace dermis
