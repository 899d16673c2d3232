#include "dermis/scene/shape_tessellation.h"

#include <cmath>

namespace dermis {

TriangleMeshDesc tessellate_disk(float height, float radius, float inner_radius, int segments) {
  TriangleMeshDesc m;
  const bool ring = inner_radius > 0;
  auto v_of = [&](float r) { return (radius - r) / (radius - inner_radius); };
  for (int i = 0; i <= segments; ++i) {  // the seam vertex is duplicated so that u runs 0..1
    float u = float(i) / float(segments);
    float phi = 2 * kPi * u;
    float c = std::cos(phi), s = std::sin(phi);
    m.positions.emplace_back(radius * c, radius * s, height);
    m.uvs.emplace_back(u, v_of(radius));
    if (ring) {
      m.positions.emplace_back(inner_radius * c, inner_radius * s, height);
      m.uvs.emplace_back(u, v_of(inner_radius));
    }
  }
  if (!ring) {
    m.positions.emplace_back(0.0f, 0.0f, height);
    m.uvs.emplace_back(0.5f, 1.0f);
  }
  m.normals.assign(m.positions.size(), Vec3(0, 0, 1));
  const uint32_t center = uint32_t(m.positions.size() - 1);
  for (int i = 0; i < segments; ++i) {
    if (ring) {
      uint32_t o0 = 2 * i, i0 = 2 * i + 1, o1 = 2 * i + 2, i1 = 2 * i + 3;
      m.indices.insert(m.indices.end(), {o0, o1, i1, o0, i1, i0});
    } else {
      m.indices.insert(m.indices.end(), {uint32_t(i), uint32_t(i + 1), center});
    }
  }
  return m;
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
