// Furnace and analytic tests of the path tracer: scenes whose exact image is known.
#include <gtest/gtest.h>

#include <cmath>

#include "dermis/render/scene_preparation.h"
#include "support/pixel_statistics.h"

namespace dermis {
namespace {

// A camera at z = -4 looking at the origin, a small image, and a uniform
// environment of radiance 1.
SceneDesc furnace_scene(int res = 12) {
  SceneDesc d;
  d.camera.camera_to_world = Transform::look_at({0, 0, -4}, {0, 0, 0}, {0, 1, 0}).inverse();
  d.camera.fov = 35;
  d.film.xres = d.film.yres = res;
  d.settings.max_depth = 100000;  // furnaces must not lose energy to the depth limit
  LightDesc env;
  env.type = LightDesc::Type::Infinite;
  env.spectrum = RGB(1);
  d.lights.push_back(env);
  return d;
}

ShapeDesc unit_sphere(int material) {
  ShapeDesc s;
  s.type = ShapeDesc::Type::Sphere;
  s.radius = 1;
  s.material = material;
  return s;
}

// |mean - expected| within 4 standard errors in every pixel and channel; a floor of
// 2e-6 absorbs float rounding where the estimator has (almost) no variance.
void expect_image_equals(const testing::PixelStatistics& st, RGB expected) {
  int failures = 0;
  for (std::size_t p = 0; p < st.mean.size(); ++p)
    for (int c = 0; c < 3; ++c) {
      double tol = std::max(4.0 * st.stderr_[p][c], 2e-6 * std::max(1.0f, expected[c]));
      if (std::abs(st.mean[p][c] - expected[c]) > tol && failures++ < 5)
        ADD_FAILURE() << "pixel " << p << " channel " << c << ": " << st.mean[p][c] << " vs " << expected[c]
                      << " (4 sigma = " << 4 * st.stderr_[p][c] << ")";
    }
  EXPECT_EQ(failures, 0);
}

TEST(Furnace, WhiteDiffuseSphereUnderUniformLightRendersOne) {
  SceneDesc d = furnace_scene();
  MaterialDesc white;
  white.type = MaterialDesc::Type::Diffuse;
  white.reflectance.value = RGB(1);
  d.materials.push_back(white);
  d.shapes.push_back(unit_sphere(0));
  Diagnostics diag;
  auto sc = build_render_scene(d, diag);
  expect_image_equals(testing::pixel_statistics(*sc, 256, 1), RGB(1));
}

TEST(Furnace, WhiteDiffuseTessellatedEllipsoidRendersOne) {
  SceneDesc d = furnace_scene();
  MaterialDesc white;
  white.reflectance.value = RGB(1);
  d.materials.push_back(white);
  ShapeDesc s = unit_sphere(0);
  s.object_to_world = Transform::scale({1, 0.6, 1});  // not a similarity: becomes a mesh
  d.shapes.push_back(s);
  Diagnostics diag;
  auto sc = build_render_scene(d, diag);
  ASSERT_EQ(sc->shapes[0].type, Shape::Type::Mesh);
  expect_image_equals(testing::pixel_statistics(*sc, 128, 2), RGB(1));
}

SceneDesc medium_sphere_scene(MaterialDesc::Type boundary, RGB sigma_s, RGB sigma_a, float g) {
  SceneDesc d = furnace_scene();
  MaterialDesc m;
  m.type = boundary;
  m.eta = 1.33f;
  d.materials.push_back(m);
  MediumDesc med;
  med.sigma_s = sigma_s;
  med.sigma_a = sigma_a;
  med.g = g;
  d.media.push_back(med);
  ShapeDesc s = unit_sphere(0);
  s.inside_medium = 0;
  s.outside_medium = -1;
  s.has_medium_interface = true;
  d.shapes.push_back(s);
  return d;
}

TEST(Furnace, NonAbsorbingMediumInIndexMatchedSphereRendersOne) {
  // Chromatic scattering coefficients exercise the spectral MIS.
  SceneDesc d = medium_sphere_scene(MaterialDesc::Type::Interface, RGB(0.5f, 2.0f, 5.0f), RGB(0), 0.0f);
  Diagnostics diag;
  auto sc = build_render_scene(d, diag);
  expect_image_equals(testing::pixel_statistics(*sc, 128, 3), RGB(1));
}

TEST(Furnace, AnisotropicMediumInIndexMatchedSphereRendersOne) {
  SceneDesc d = medium_sphere_scene(MaterialDesc::Type::Interface, RGB(3.0f), RGB(0), 0.7f);
  Diagnostics diag;
  auto sc = build_render_scene(d, diag);
  expect_image_equals(testing::pixel_statistics(*sc, 128, 4), RGB(1));
}

TEST(Furnace, NonAbsorbingMediumInDielectricSphereRendersOne) {
  // Radiance inside is eta^2 L; the 1/eta^2 scaling at refraction brings it back to L.
  SceneDesc d = medium_sphere_scene(MaterialDesc::Type::Dielectric, RGB(1.0f, 2.0f, 4.0f), RGB(0), 0.0f);
  Diagnostics diag;
  auto sc = build_render_scene(d, diag);
  expect_image_equals(testing::pixel_statistics(*sc, 128, 5), RGB(1));
}

TEST(Analytic, AbsorbingSlabTransmittanceIsBeerLambert) {
  // A slab |z| < 0.25 (thickness 0.5) of purely absorbing chromatic medium behind an
  // index-matched boundary; the camera looks through it at the uniform environment.
  SceneDesc d = furnace_scene(8);
  d.camera.fov = 10;
  MaterialDesc iface;
  iface.type = MaterialDesc::Type::Interface;
  d.materials.push_back(iface);
  MediumDesc med;
  med.sigma_a = RGB(0.5f, 1.0f, 3.0f);
  med.sigma_s = RGB(0);
  med.scale = 2;
  d.media.push_back(med);
  // Two large parallel quads facing away from each other: a box open at the sides
  // is enough, since the camera only sees through the front and back faces.
  for (float z : {-0.25f, 0.25f}) {
    ShapeDesc q;
    q.material = 0;
    q.mesh.positions = {{-50, -50, z}, {50, -50, z}, {50, 50, z}, {-50, 50, z}};
    q.mesh.indices = {0, 1, 2, 0, 2, 3};
    q.inside_medium = 0;
    q.outside_medium = -1;
    q.has_medium_interface = true;
    // Normals point out of the slab: the front quad faces -z, the back one +z.
    q.reverse_orientation = z < 0;
    d.shapes.push_back(q);
  }
  Diagnostics diag;
  auto sc = build_render_scene(d, diag);
  // Check the normal orientation convention the test relies on.
  SurfaceHit hit;
  ASSERT_TRUE(sc->embree->intersect(Ray{{0, 0, -4}, {0, 0, 1}}, hit));
  ASSERT_LT(hit.ng.z, 0) << "front face must face the camera (outside)";
  RGB expected = exp(med.sigma_a * (-med.scale * 0.5f));
  expect_image_equals(testing::pixel_statistics(*sc, 512, 6), expected);
}

// The furnace tests above must be able to fail: an absorbing medium darkens the sphere.
TEST(Furnace, AbsorbingMediumIsDetectedAsNotOne) {
  SceneDesc d = medium_sphere_scene(MaterialDesc::Type::Interface, RGB(1.0f), RGB(0.3f), 0.0f);
  Diagnostics diag;
  auto sc = build_render_scene(d, diag);
  auto st = testing::pixel_statistics(*sc, 128, 3);
  int centre = (d.film.yres / 2) * d.film.xres + d.film.xres / 2;
  EXPECT_LT(st.mean[centre][0] + 4 * st.stderr_[centre][0], 1.0f);
}

}  // namespace
}  // namespace dermis
