// Loop subdivision (loop_subdivision.h). Independent references: Euler's counts for
// refinement (V' = V + E, F' = 4F), the limit point of a vertex being invariant under
// refinement (it is the dominant left eigenvector of the subdivision matrix, Loop 1987),
// the regular box-spline limit mask (1/2 centre, 1/12 per neighbour), planarity, and the
// refined meshes' own face normals converging to the limit normals.
#include "dermis/scene/loop_subdivision.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <stdexcept>

#include "dermis/scene/scene_test_util.h"

namespace dermis {
namespace {

LoopMesh tetrahedron() {
  return {{{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}}, {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2}};
}

LoopMesh octahedron() {
  return {{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}},
          {4, 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 5, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3}};
}

// A 4 x 3 grid of quads (two triangles each) over [0,4] x [0,3], bent into z = f(x, y)
// (planar when bend = 0), wound counter-clockwise seen from +z.
LoopMesh grid(float bend) {
  LoopMesh m;
  for (int j = 0; j <= 3; ++j)
    for (int i = 0; i <= 4; ++i) m.positions.emplace_back(float(i), float(j), bend * float(i * i - j * j + i * j) / 8);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) {
      uint32_t a = uint32_t(j * 5 + i), b = a + 1, c = a + 5, d = c + 1;
      m.indices.insert(m.indices.end(), {a, b, d, a, d, c});
    }
  return m;
}

// Every directed edge once, and its reverse once: closed and consistently oriented.
bool closed_and_oriented(const LoopMesh& m) {
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (std::size_t t = 0; t < m.indices.size() / 3; ++t)
    for (int k = 0; k < 3; ++k) ++directed[{m.indices[3 * t + k], m.indices[3 * t + (k + 1) % 3]}];
  for (const auto& [e, n] : directed) {
    auto r = directed.find({e.second, e.first});
    if (n != 1 || r == directed.end() || r->second != 1) return false;
  }
  return true;
}

Vec3 face_normal(const std::vector<Vec3>& p, const uint32_t* tri) {
  return normalize(cross(p[tri[1]] - p[tri[0]], p[tri[2]] - p[tri[0]]));
}

TEST(LoopSubdivision, VertexAndTriangleCountsPerLevelAreExact) {
  LoopMesh m = tetrahedron();
  std::size_t v = 4, e = 6, f = 4;
  for (int level = 1; level <= 4; ++level) {
    m = loop_refine(m);
    v += e;             // one new vertex per edge
    e = 2 * e + 3 * f;  // each edge split in two, three new edges inside each triangle
    f *= 4;
    EXPECT_EQ(m.positions.size(), v) << "level " << level;
    EXPECT_EQ(m.indices.size(), 3 * f) << "level " << level;
    EXPECT_EQ(v - e + f, 2u) << "Euler characteristic of a sphere";
    EXPECT_TRUE(closed_and_oriented(m)) << "level " << level;
  }
}

TEST(LoopSubdivision, LimitPointsAreInvariantUnderRefinement) {
  // Interior vertices of valence 3 (tetrahedron), 4 (octahedron), 6 and boundary vertices
  // of valence 2, 3, 4 (the bent grid's corners and edges): the limit point of an old
  // vertex is the same computed before or after one more refinement.
  for (const LoopMesh& m0 : {tetrahedron(), octahedron(), grid(1.0f), loop_refine(grid(1.0f))}) {
    const std::vector<Vec3> before = loop_limit_positions(m0);
    const std::vector<Vec3> after = loop_limit_positions(loop_refine(m0));
    for (std::size_t v = 0; v < m0.positions.size(); ++v)
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(before[v][c], after[v][c], 2e-6f) << "vertex " << v;
  }
}

TEST(LoopSubdivision, LimitNormalsAreInvariantUnderRefinement) {
  // The limit tangents are left eigenvectors of the subdivision matrix too: the normal at
  // an old vertex is the same before and after one more refinement.
  for (const LoopMesh& m0 : {tetrahedron(), octahedron(), grid(1.0f), loop_refine(grid(1.0f))}) {
    const std::vector<Vec3> before = loop_limit_normals(m0);
    const std::vector<Vec3> after = loop_limit_normals(loop_refine(m0));
    for (std::size_t v = 0; v < m0.positions.size(); ++v)
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(before[v][c], after[v][c], 2e-6f) << "vertex " << v;
  }
}

TEST(LoopSubdivision, RegularVertexUsesTheBoxSplineLimitMask) {
  // Valence 6 in the refined grid's interior: limit = 1/2 v + 1/12 sum of neighbours (the
  // quartic box spline's value at a vertex).
  LoopMesh m = loop_refine(grid(1.0f));
  const std::vector<Vec3> limit = loop_limit_positions(m);
  // Vertex (2, 1) of the original grid (index 7) is interior with the six grid neighbours
  // (1,0) (2,0)... of the refined mesh's edge vertices; find them through the triangles.
  const uint32_t v = 7;
  std::map<uint32_t, int> ring;
  for (std::size_t t = 0; t < m.indices.size() / 3; ++t)
    for (int k = 0; k < 3; ++k)
      if (m.indices[3 * t + k] == v) {
        ring[m.indices[3 * t + (k + 1) % 3]]++;
        ring[m.indices[3 * t + (k + 2) % 3]]++;
      }
  ASSERT_EQ(ring.size(), 6u);
  Vec3d expect = Vec3d(m.positions[v]) * 0.5;
  for (const auto& [q, n] : ring) expect = expect + Vec3d(m.positions[q]) / 12.0;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(limit[v][c], float(expect[c]), 1e-6f);
}

TEST(LoopSubdivision, PlanarMeshStaysPlanarWithItsBoundary) {
  TriangleMeshDesc s = loop_subdivision_surface(grid(0).positions, grid(0).indices, 3);
  EXPECT_EQ(s.indices.size(), 3u * 24 * 64);
  for (std::size_t i = 0; i < s.positions.size(); ++i) {
    EXPECT_EQ(s.positions[i].z, 0.0f);
    EXPECT_EQ(s.normals[i], Vec3(0, 0, 1));
    EXPECT_GE(s.positions[i].x, 0.0f);  // the boundary spline stays in the grid's hull
    EXPECT_LE(s.positions[i].x, 4.0f);
    EXPECT_GE(s.positions[i].y, 0.0f);
    EXPECT_LE(s.positions[i].y, 3.0f);
  }
}

// Smoother at every level: the largest angle between the normals of neighbouring
// triangles, and between each limit normal and the normals of the limit mesh's
// triangles around it, fall by at least 30% per level (on a smooth surface both shrink
// like the edge length, halved per level). `facing(p, n)`: n points to the right side at p.
template <class Facing>
void expect_converges(const LoopMesh& control, Facing facing) {
  double prev_crease = 10, prev_normal_gap = 10;
  for (int levels = 1; levels <= 5; ++levels) {
    const TriangleMeshDesc s = loop_subdivision_surface(control.positions, control.indices, levels);
    std::map<std::pair<uint32_t, uint32_t>, std::size_t> face_of_edge;
    for (std::size_t t = 0; t < s.indices.size() / 3; ++t)
      for (int k = 0; k < 3; ++k) face_of_edge[{s.indices[3 * t + k], s.indices[3 * t + (k + 1) % 3]}] = t;
    double crease = 0, normal_gap = 0;
    for (const auto& [e, t] : face_of_edge) {
      const Vec3 nt = face_normal(s.positions, &s.indices[3 * t]);
      auto other = face_of_edge.find({e.second, e.first});
      if (other != face_of_edge.end()) {
        const Vec3 nu = face_normal(s.positions, &s.indices[3 * other->second]);
        crease = std::max(crease, std::acos(std::clamp(double(dot(nt, nu)), -1.0, 1.0)));
      }
      const Vec3 vn = s.normals[e.first];
      normal_gap = std::max(normal_gap, std::acos(std::clamp(double(dot(vn, nt)), -1.0, 1.0)));
      EXPECT_TRUE(facing(s.positions[e.first], vn)) << "level " << levels << " vertex " << e.first;
    }
    EXPECT_LT(crease, 0.7 * prev_crease) << "level " << levels;
    EXPECT_LT(normal_gap, 0.7 * prev_normal_gap) << "level " << levels;
    prev_crease = crease;
    prev_normal_gap = normal_gap;
  }
}

TEST(LoopSubdivision, OctahedronConvergesToASmoothClosedSurface) {
  LoopMesh m = octahedron();
  for (int l = 0; l < 5; ++l) {
    m = loop_refine(m);
    ASSERT_TRUE(closed_and_oriented(m));
  }
  expect_converges(octahedron(), [](Vec3 p, Vec3 n) { return dot(n, p) > 0; });  // outward
}

// The bent open grid: the boundary rules (limit points and Hoppe's tangents) converge too.
TEST(LoopSubdivision, OpenBentMeshConvergesWithItsBoundary) {
  expect_converges(grid(1.0f), [](Vec3, Vec3 n) { return n.z > 0; });  // wound counter-clockwise from +z
}

TEST(LoopSubdivision, NonManifoldMeshesAreRefused) {
  // Three triangles on one edge.
  LoopMesh fin{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}}, {0, 1, 2, 1, 0, 3, 0, 1, 4}};
  EXPECT_THROW(loop_refine(fin), std::invalid_argument);
  // Two triangles of opposite winding on one edge.
  LoopMesh flipped{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}}, {0, 1, 2, 0, 1, 3}};
  EXPECT_THROW(loop_refine(flipped), std::invalid_argument);
  // Two fans meeting at one vertex (a bow tie).
  LoopMesh bowtie{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}}, {0, 1, 2, 0, 3, 4}};
  EXPECT_THROW(loop_refine(bowtie), std::invalid_argument);
  EXPECT_THROW(loop_subdivision_surface(tetrahedron().positions, tetrahedron().indices, 20), std::invalid_argument);
}

TEST(LoopSubdivision, ParsedAsPbrtV4Shape) {
  SceneDesc s = test::parse_world(
      "LightSource \"point\"\n"
      "Shape \"loopsubdiv\" \"point3 P\" [1 1 1  1 -1 -1  -1 1 -1  -1 -1 1] \"integer indices\" [0 1 2 0 3 1 0 2 3 1 3 "
      "2]\n"
      "Shape \"loopsubdiv\" \"integer levels\" 1 \"point3 P\" [1 1 1  1 -1 -1  -1 1 -1  -1 -1 1] "
      "\"integer indices\" [0 1 2 0 3 1 0 2 3 1 3 2]\n");
  EXPECT_TRUE(s.diagnostics.warnings.empty());
  EXPECT_EQ(s.shapes[0].mesh.indices.size(), 3u * 4 * 64);  // levels default 3
  EXPECT_EQ(s.shapes[0].mesh.normals.size(), s.shapes[0].mesh.positions.size());
  EXPECT_EQ(s.shapes[1].mesh.indices.size(), 3u * 4 * 4);
  try {
    test::parse_world(
        "Shape \"loopsubdiv\" \"point3 P\" [0 0 0 1 0 0 0 1 0 0 -1 0 0 0 1] "
        "\"integer indices\" [0 1 2 1 0 3 0 1 4]\n");
    ADD_FAILURE() << "a non-manifold mesh was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("more than two triangles"), std::string::npos) << e.what();
  }
  EXPECT_THROW(test::parse_world("Shape \"loopsubdiv\" \"point3 P\" [0 0 0 1 0 0 0 1 0]\n"), SceneError);
}

}  // namespace
}  // namespace dermis
