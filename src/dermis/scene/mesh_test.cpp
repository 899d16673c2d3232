// Shapes: inline meshes, PLY (ASCII, binary, triangle strips), OBJ through Assimp, and
// the tessellated disk and bilinear patches.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "dermis/scene/parser.h"
#include "dermis/scene/ply_reader.h"
#include "dermis/scene/scene_test_util.h"
#include "dermis/scene/shape_tessellation.h"

namespace dermis {
namespace {

using test::parse_world;
using Tri = std::array<std::array<float, 3>, 3>;

Vec3 face_normal(const TriangleMeshDesc& m, size_t t) {
  Vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]], c = m.positions[m.indices[3 * t + 2]];
  return cross(b - a, c - a);
}

// Triangles as position triples, rotated so the smallest vertex comes first (winding kept).
std::set<Tri> triangles(const TriangleMeshDesc& m) {
  std::set<Tri> out;
  for (size_t t = 0; t < m.indices.size() / 3; ++t) {
    Tri tri;
    for (int k = 0; k < 3; ++k) {
      Vec3 p = m.positions[m.indices[3 * t + k]];
      tri[k] = {p.x, p.y, p.z};
    }
    int first = int(std::min_element(tri.begin(), tri.end()) - tri.begin());
    std::rotate(tri.begin(), tri.begin() + first, tri.end());
    out.insert(tri);
  }
  return out;
}

Tri tri(std::array<float, 3> a, std::array<float, 3> b, std::array<float, 3> c) {
  Tri t{a, b, c};
  int first = int(std::min_element(t.begin(), t.end()) - t.begin());
  std::rotate(t.begin(), t.begin() + first, t.end());
  return t;
}

TEST(ShapeTriangleMesh, ValuesAsWritten) {
  SceneDesc s = parse_world(
      "Shape \"trianglemesh\" \"point3 P\" [0 0 0  1 0 0  1 1 0  0 1 0] \"integer indices\" [0 1 2 0 2 3]\n"
      "  \"normal N\" [0 0 1 0 0 1 0 0 1 0 0 1] \"point2 uv\" [0 0 1 0 1 1 0 1]\n"
      "Shape \"trianglemesh\" \"point3 P\" [0 0 0  1 0 0  0 1 0]\n");
  ASSERT_EQ(s.shapes.size(), 2u);
  const TriangleMeshDesc& m = s.shapes[0].mesh;
  EXPECT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(m.positions[2], Vec3(1, 1, 0));
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(m.normals.size(), 4u);
  EXPECT_FLOAT_EQ(m.uvs[2].x, 1);
  EXPECT_EQ(s.shapes[1].mesh.indices, (std::vector<uint32_t>{0, 1, 2}));  // implicit for 3 vertices
  EXPECT_EQ(s.shapes[0].material, -1);
}

TEST(ShapeSphere, RadiusAndPartialTessellated) {
  SceneDesc s = parse_world(
      "LightSource \"point\"\nShape \"sphere\" \"float radius\" 2.5\nShape \"sphere\" \"float zmax\" 0.5\n");
  EXPECT_EQ(s.shapes[0].type, ShapeDesc::Type::Sphere);
  EXPECT_FLOAT_EQ(s.shapes[0].radius, 2.5f);
  EXPECT_EQ(s.shapes[1].type, ShapeDesc::Type::TriangleMesh);  // quadric_shapes_test.cpp
  EXPECT_TRUE(s.diagnostics.warnings.empty());
}

TEST(ShapeDisk, TessellatedFanFacesPlusZAndHasPolygonArea) {
  SceneDesc s = parse_world("Shape \"disk\" \"float radius\" 2 \"float height\" 0.5\n");
  const TriangleMeshDesc& m = s.shapes[0].mesh;
  ASSERT_EQ(m.indices.size(), 3u * kDiskSegments);
  double area = 0;
  for (size_t t = 0; t < m.indices.size() / 3; ++t) {
    Vec3 n = face_normal(m, t);
    EXPECT_GT(n.z, 0) << "triangle " << t;
    area += 0.5 * length(n);
  }
  // Area of the regular 256-gon inscribed in the circle: (n/2) r^2 sin(2 pi / n).
  double expected = 0.5 * kDiskSegments * 4.0 * std::sin(2 * kPiD / kDiskSegments);
  EXPECT_NEAR(area, expected, 1e-5 * expected);
  for (const Vec3& p : m.positions) EXPECT_FLOAT_EQ(p.z, 0.5f);
}

TEST(ShapeDisk, RingWithInnerRadius) {
  TriangleMeshDesc m = tessellate_disk(0, 1, 0.5f, 64);
  double area = 0;
  for (size_t t = 0; t < m.indices.size() / 3; ++t) {
    EXPECT_GT(face_normal(m, t).z, 0);
    area += 0.5 * length(face_normal(m, t));
  }
  double expected = 0.5 * 64 * (1.0 - 0.25) * std::sin(2 * kPiD / 64);
  EXPECT_NEAR(area, expected, 1e-5);
}

TEST(ShapeBilinear, PlanarPatchIsTwoTrianglesWithPbrtOrientation) {
  SceneDesc s = parse_world("Shape \"bilinearmesh\" \"point3 P\" [0 0 0  2 0 0  0 1 0  2 1 0]\n");
  const TriangleMeshDesc& m = s.shapes[0].mesh;
  ASSERT_EQ(m.indices.size(), 6u);
  for (size_t t = 0; t < 2; ++t) EXPECT_GT(face_normal(m, t).z, 0);  // dp/du x dp/dv = +z
  EXPECT_EQ(triangles(m), (std::set<Tri>{tri({0, 0, 0}, {2, 0, 0}, {2, 1, 0}), tri({0, 0, 0}, {2, 1, 0}, {0, 1, 0})}));
}

TEST(ShapeBilinear, NonPlanarPatchIsAGridOnTheSurface) {
  // Hyperbolic paraboloid z = u v over the unit square.
  SceneDesc s =
      parse_world("Shape \"bilinearmesh\" \"point3 P\" [0 0 0  1 0 0  0 1 0  1 1 1] \"integer indices\" [0 1 2 3]\n");
  const TriangleMeshDesc& m = s.shapes[0].mesh;
  EXPECT_EQ(m.indices.size(), size_t(6 * kBilinearGrid * kBilinearGrid));
  for (const Vec3& p : m.positions) EXPECT_NEAR(p.z, p.x * p.y, 1e-6);
  for (size_t t = 0; t < m.indices.size() / 3; ++t) EXPECT_GT(face_normal(m, t).z, 0);
}

TEST(ShapePly, AsciiWithQuadSplitNormalsAndUv) {
  test::TempDir dir;
  dir.write("q.ply",
            "ply\nformat ascii 1.0\ncomment test\nelement vertex 4\nproperty float x\nproperty float y\n"
            "property float z\nproperty float nx\nproperty float ny\nproperty float nz\nproperty float u\n"
            "property float v\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
            "0 0 0 0 0 1 0 0\n1 0 0 0 0 1 1 0\n1 1 0 0 0 1 1 1\n0 1 0 0 0 1 0 1\n4 0 1 2 3\n");
  SceneDesc s = parse_world("Shape \"plymesh\" \"string filename\" \"q.ply\"\n", dir.path());
  const TriangleMeshDesc& m = s.shapes[0].mesh;
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  ASSERT_EQ(m.normals.size(), 4u);
  EXPECT_EQ(m.normals[3], Vec3(0, 0, 1));
  ASSERT_EQ(m.uvs.size(), 4u);
  EXPECT_FLOAT_EQ(m.uvs[2].y, 1);
}

void put_f32(std::string& s, float v, bool big_endian) {
  char b[4];
  std::memcpy(b, &v, 4);
  if (big_endian) std::reverse(b, b + 4);
  s.append(b, 4);
}
void put_i32(std::string& s, int32_t v, bool big_endian) {
  char b[4];
  std::memcpy(b, &v, 4);
  if (big_endian) std::reverse(b, b + 4);
  s.append(b, 4);
}

TEST(ShapePly, BinaryTriangleStripsKeepOneWinding) {
  // Two strips separated by -1, over a column of points in the z = 0 plane; every
  // triangle of a correctly decoded strip faces +z. The repeated 4 is a strip joiner.
  const float pts[][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 2, 0}, {5, 0, 0}, {6, 0, 0}, {5, 1, 0}};
  const int32_t strip[] = {0, 1, 2, 3, 4, 4, -1, 5, 6, 7};
  for (bool be : {false, true}) {
    std::string ply = std::string("ply\nformat ") + (be ? "binary_big_endian" : "binary_little_endian") +
                      " 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
                      "element tristrips 1\nproperty list int int vertex_indices\nend_header\n";
    for (const auto& p : pts)
      for (float c : p) put_f32(ply, c, be);
    put_i32(ply, int32_t(std::size(strip)), be);
    for (int32_t i : strip) put_i32(ply, i, be);
    test::TempDir dir;
    std::string path = dir.write("strip.ply", ply);
    TriangleMeshDesc m = read_ply(path);
    ASSERT_EQ(m.indices.size(), 12u) << (be ? "big endian" : "little endian");
    EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 2, 1, 3, 2, 3, 4, 5, 6, 7}));
    for (size_t t = 0; t < 4; ++t) EXPECT_GT(face_normal(m, t).z, 0) << "triangle " << t;
  }
}

TEST(ShapePly, IgeaBinaryWithTriangleStrips) {
  // scenes/meshes/igea.ply: binary PLY with triangle strips (scenes/meshes/SOURCES.md).
  const std::string path = std::string(DERMIS_SOURCE_DIR) + "/scenes/meshes/igea.ply";
  ASSERT_TRUE(std::filesystem::exists(path)) << path;
  SceneDesc s = parse_scene_string("WorldBegin\nShape \"plymesh\" \"string filename\" \"" + path + "\"\n");
  const TriangleMeshDesc& m = s.shapes[0].mesh;
  const size_t nv = m.positions.size(), nt = m.indices.size() / 3;
  EXPECT_EQ(nv, 134345u);
  // A closed-ish genus-0 scan has about twice as many triangles as vertices.
  EXPECT_GT(nt, 19 * nv / 10);
  EXPECT_LT(nt, 21 * nv / 10);
  // Consistent winding: in an oriented manifold each directed edge occurs once.
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) ++directed[{m.indices[3 * t + k], m.indices[3 * t + (k + 1) % 3]}];
  size_t repeated = 0;
  for (const auto& [edge, count] : directed) repeated += count > 1;
  EXPECT_LT(double(repeated), 1e-3 * double(directed.size())) << repeated << " directed edges repeated";
}

void expect_same_mesh(const TriangleMeshDesc& a, const TriangleMeshDesc& b) {
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.normals, b.normals);
  ASSERT_EQ(a.uvs.size(), b.uvs.size());
  for (size_t i = 0; i < a.uvs.size(); ++i) {
    EXPECT_EQ(a.uvs[i].x, b.uvs[i].x) << "uv " << i;
    EXPECT_EQ(a.uvs[i].y, b.uvs[i].y) << "uv " << i;
  }
  EXPECT_EQ(a.indices, b.indices);
}

TEST(ShapePly, GzipAsciiAndBinaryReadAsThePlainFile) {
  test::TempDir dir;
  const std::string ascii =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "property float nx\nproperty float ny\nproperty float nz\nproperty float u\nproperty float v\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 0 0 1 0 0\n1 0 0 0 0 1 1 0\n1 1 0 0 0 1 1 1\n0 1 0 0 0 1 0 1\n4 0 1 2 3\n";
  std::string binary;
  {
    std::ifstream in(std::string(DERMIS_SOURCE_DIR) + "/scenes/meshes/igea.ply", std::ios::binary);
    binary.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    ASSERT_GT(binary.size(), 1000000u) << "scenes/meshes/igea.ply";
  }
  for (const auto& [name, ply] : {std::pair<std::string, std::string>{"ascii", ascii}, {"binary", binary}}) {
    SCOPED_TRACE(name);
    TriangleMeshDesc plain = read_ply(dir.write(name + ".ply", ply));
    ASSERT_FALSE(plain.indices.empty());
    const std::string z = test::gzip(ply, 1);
    expect_same_mesh(read_ply(dir.write(name + ".ply.gz", z)), plain);
    // Detected by the magic, not the extension.
    expect_same_mesh(read_ply(dir.write(name + "-gz.ply", z)), plain);
    // Through the scene parser.
    SceneDesc s = parse_world("Shape \"plymesh\" \"string filename\" \"" + name + ".ply.gz\"\n", dir.path());
    ASSERT_EQ(s.shapes.size(), 1u);
    expect_same_mesh(s.shapes[0].mesh, plain);
  }
}

TEST(ShapeObj, AssimpKeepsWindingAndMergesMeshes) {
  test::TempDir dir;
  dir.write("m.obj",
            "o first\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n"
            "o second\nv 0 0 5\nv 0 1 5\nv 1 0 5\nvt 0 0\nf 5/1 6/1 7/1\n");
  SceneDesc s = parse_world("Shape \"objmesh\" \"string filename\" \"m.obj\"\n", dir.path());
  ASSERT_EQ(s.shapes.size(), 1u);
  const TriangleMeshDesc& m = s.shapes[0].mesh;
  EXPECT_EQ(m.indices.size(), 9u);
  EXPECT_TRUE(m.normals.empty());  // the file has none and none are generated
  EXPECT_EQ(m.uvs.size(), m.positions.size());
  std::set<Tri> got = triangles(m);
  // The quad fans from its first vertex in the written order; the second object keeps its (clockwise) order.
  std::set<Tri> want{tri({0, 0, 0}, {1, 0, 0}, {1, 1, 0}), tri({0, 0, 0}, {1, 1, 0}, {0, 1, 0}),
                     tri({0, 0, 5}, {0, 1, 5}, {1, 0, 5})};
  EXPECT_EQ(got, want);
}

// Assimp's OBJ reader writes a vertex per face corner; the import merges those identical in
// position, normal and uv (the file's own sharing) and keeps those that differ in any.
TEST(ShapeObj, CornersWithTheSameAttributesShareAVertex) {
  test::TempDir dir;
  // Two triangles sharing an edge (v1, v3) with the same uv and normal there, and a third
  // that meets v1 with another uv: v1 appears as two vertices, v3 as one.
  dir.write("m.obj",
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5\nvn 0 0 1\n"
            "f 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\nf 4/4/1 2/2/1 1/5/1\n");
  SceneDesc s = parse_world("Shape \"objmesh\" \"string filename\" \"m.obj\"\n", dir.path());
  ASSERT_EQ(s.shapes.size(), 1u);
  const TriangleMeshDesc& m = s.shapes[0].mesh;
  ASSERT_EQ(m.indices.size(), 9u);
  EXPECT_EQ(m.positions.size(), 5u);  // the four (v, vt) pairs of the first two faces and (v1, vt5)
  ASSERT_EQ(m.normals.size(), m.positions.size());
  ASSERT_EQ(m.uvs.size(), m.positions.size());
  // The shared edge is one pair of vertex indices in both triangles.
  EXPECT_EQ(m.indices[0], m.indices[3]);
  EXPECT_EQ(m.indices[2], m.indices[4]);
  // Corner for corner, every attribute is the file's.
  const Vec3 p[] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 0}};
  const Vec2 uv[] = {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}, {0, 1}, {1, 0}, {0.5f, 0.5f}};
  for (int k = 0; k < 9; ++k) {
    const uint32_t i = m.indices[std::size_t(k)];
    EXPECT_EQ(m.positions[i], p[k]) << "corner " << k;
    EXPECT_EQ(m.uvs[i].x, uv[k].x) << "corner " << k;
    EXPECT_EQ(m.uvs[i].y, uv[k].y) << "corner " << k;
    EXPECT_EQ(m.normals[i], Vec3(0, 0, 1)) << "corner " << k;
  }
  EXPECT_NE(m.indices[0], m.indices[8]);  // v1 with another uv is a vertex of its own
}

}  // namespace
}  // namespace dermis
