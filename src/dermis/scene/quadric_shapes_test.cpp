// pbrt-v4's quadrics as Dermis tessellates them: cylinder, partial sphere, partial disk.
// References: the analytic surfaces (every vertex on them), the areas of the inscribed
// polygons / Archimedes' zone area, and pbrt-v4's (u, v) and normal conventions.
#include <gtest/gtest.h>

#include <cmath>

#include "dermis/scene/scene_test_util.h"
#include "dermis/scene/shape_tessellation.h"

namespace dermis {
namespace {

using test::parse_world;

Vec3d face_area_vector(const TriangleMeshDesc& m, std::size_t t) {
  const Vec3d a(m.positions[m.indices[3 * t]]), b(m.positions[m.indices[3 * t + 1]]),
      c(m.positions[m.indices[3 * t + 2]]);
  return cross(b - a, c - a) * 0.5;
}

double phi_of(Vec3 p) {
  double phi = std::atan2(double(p.y), double(p.x));
  return phi < 0 ? phi + 2 * kPiD : phi;
}

TEST(ShapeCylinder, PbrtDefaultsOutwardNormalsAndUv) {
  SceneDesc s = parse_world("LightSource \"point\"\nShape \"cylinder\"\n");  // lit: no "no lights" warning
  ASSERT_EQ(s.shapes.size(), 1u);
  EXPECT_TRUE(s.diagnostics.warnings.empty());
  const TriangleMeshDesc& m = s.shapes[0].mesh;
  ASSERT_EQ(m.indices.size(), 6u * kDiskSegments);
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    const Vec3 p = m.positions[i];
    EXPECT_NEAR(std::hypot(p.x, p.y), 1.0, 1e-6);  // radius 1
    EXPECT_NEAR(m.uvs[i].y, (p.z + 1) / 2, 1e-6);  // v = (z - zmin) / (zmax - zmin), z in [-1, 1]
    if (m.uvs[i].x > 1e-4f && m.uvs[i].x < 1 - 1e-4f) {
      EXPECT_NEAR(m.uvs[i].x, phi_of(p) / (2 * kPiD), 1e-5);
    }
    EXPECT_NEAR(m.normals[i].x, p.x, 1e-6);  // away from the axis
    EXPECT_NEAR(m.normals[i].z, 0, 1e-7);
  }
  double area = 0;
  for (std::size_t t = 0; t < m.indices.size() / 3; ++t) {
    const Vec3d n = face_area_vector(m, t);
    const Vec3 c =
        (m.positions[m.indices[3 * t]] + m.positions[m.indices[3 * t + 1]] + m.positions[m.indices[3 * t + 2]]) / 3.0f;
    EXPECT_GT(dot(n, Vec3d(c.x, c.y, 0)), 0) << "triangle " << t << " faces the axis";
    area += length(n);
  }
  // The inscribed prism: perimeter 2 n sin(pi / n) times the height 2.
  EXPECT_NEAR(area, 2 * kDiskSegments * std::sin(kPiD / kDiskSegments) * 2, 1e-5 * area);
}

TEST(ShapeCylinder, PartialTurnAndErrors) {
  SceneDesc s =
      parse_world("Shape \"cylinder\" \"float radius\" 2 \"float zmin\" 0 \"float zmax\" 3 \"float phimax\" 90\n");
  const TriangleMeshDesc& m = s.shapes[0].mesh;
  EXPECT_EQ(m.indices.size(), 6u * kDiskSegments / 4);  // a quarter of the segments
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    EXPECT_GE(m.positions[i].x, -1e-6f);
    EXPECT_GE(m.positions[i].y, -1e-6f);
    EXPECT_NEAR(m.uvs[i].x, phi_of(m.positions[i]) / (kPiD / 2), 1e-5);  // u = phi / phimax
    EXPECT_NEAR(m.uvs[i].y, m.positions[i].z / 3, 1e-6);
  }
  EXPECT_THROW(parse_world("Shape \"cylinder\" \"float zmin\" 1 \"float zmax\" 1\n"), SceneError);
  EXPECT_THROW(parse_world("Shape \"cylinder\" \"float radius\" 0\n"), SceneError);
}

TEST(ShapeSphere, PartialSphereIsTheZoneArchimedesGives) {
  SceneDesc s = parse_world(
      "LightSource \"point\"\n"
      "Shape \"sphere\" \"float radius\" 2 \"float zmin\" -1 \"float zmax\" 1.5 \"float phimax\" 270\n"
      "Shape \"sphere\" \"float radius\" 2\n");
  EXPECT_TRUE(s.diagnostics.warnings.empty());
  ASSERT_EQ(s.shapes[0].type, ShapeDesc::Type::TriangleMesh);
  EXPECT_EQ(s.shapes[1].type, ShapeDesc::Type::Sphere);  // full spheres stay analytic
  const TriangleMeshDesc& m = s.shapes[0].mesh;
  const double theta_zmin = std::acos(-0.5), theta_zmax = std::acos(0.75);
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    const Vec3 p = m.positions[i];
    EXPECT_NEAR(length(p), 2, 2e-6);
    EXPECT_GE(p.z, -1 - 1e-6f);
    EXPECT_LE(p.z, 1.5f + 1e-6f);
    // pbrt-v4: v = (theta - theta_zmin) / (theta_zmax - theta_zmin): 0 at zmin, 1 at zmax.
    const double theta = std::acos(std::clamp(double(p.z) / length(Vec3d(p)), -1.0, 1.0));
    EXPECT_NEAR(m.uvs[i].y, (theta - theta_zmin) / (theta_zmax - theta_zmin), 2e-4);
    if (m.uvs[i].x > 1e-4f && m.uvs[i].x < 1 - 1e-4f) {
      EXPECT_NEAR(m.uvs[i].x, phi_of(p) / (1.5 * kPiD), 1e-5);
    }
    EXPECT_NEAR(dot(m.normals[i], p / 2.0f), 1, 1e-5);  // outward
  }
  double area = 0;
  for (std::size_t t = 0; t < m.indices.size() / 3; ++t) {
    const Vec3d n = face_area_vector(m, t);
    EXPECT_GT(dot(n, Vec3d(m.positions[m.indices[3 * t]])), 0) << "triangle " << t << " faces inward";
    area += length(n);
  }
  // Archimedes: a zone of height h on a sphere of radius r has area 2 pi r h; phimax takes 3/4
  // of it. The inscribed mesh falls short by about (pi/256)^2/6 + (pi/128)^2/6 = 1.2e-4.
  const double zone = 2 * kPiD * 2 * 2.5 * 0.75;
  EXPECT_LT(area, zone);
  EXPECT_NEAR(area, zone, 3e-4 * zone);
}

TEST(ShapeSphere, CapsEndInASinglePole) {
  // A hemisphere z >= 0: the pole z = r is one point and no triangle is degenerate.
  SceneDesc s = parse_world("Shape \"sphere\" \"float zmin\" 0\n");
  const TriangleMeshDesc& m = s.shapes[0].mesh;
  int at_pole = 0;
  for (const Vec3& p : m.positions) at_pole += p == Vec3(0, 0, 1);
  EXPECT_EQ(at_pole, kDiskSegments + 1);
  for (std::size_t t = 0; t < m.indices.size() / 3; ++t) EXPECT_GT(length(face_area_vector(m, t)), 0) << t;
  EXPECT_THROW(parse_world("Shape \"sphere\" \"float zmin\" 1 \"float zmax\" 2\n"), SceneError);
}

TEST(ShapeDisk, PartialDiskCoversItsAngle) {
  SceneDesc s = parse_world("LightSource \"point\"\nShape \"disk\" \"float phimax\" 180 \"float innerradius\" 0.5\n");
  EXPECT_TRUE(s.diagnostics.warnings.empty());
  const TriangleMeshDesc& m = s.shapes[0].mesh;
  double area = 0;
  for (std::size_t t = 0; t < m.indices.size() / 3; ++t) {
    const Vec3d n = face_area_vector(m, t);
    EXPECT_GT(n.z, 0);
    area += length(n);
  }
  EXPECT_NEAR(area, 0.5 * (kDiskSegments / 2) * (1.0 - 0.25) * std::sin(2 * kPiD / kDiskSegments), 1e-6);
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    EXPECT_GE(m.positions[i].y, -1e-6f);
    const double r = std::hypot(m.positions[i].x, m.positions[i].y);
    EXPECT_NEAR(m.uvs[i].y, (1 - r) / 0.5, 1e-5);  // pbrt: v = (radius - r) / (radius - innerradius)
  }
}

}  // namespace
}  // namespace dermis
